#pragma once
// How the viewer's mouse and keys move the virtual camera: pure functions of the camera's
// parameters, so they are tested without a window.
//
// The pivot of orbiting is the point in focus at the frame's centre (e_c + d_o * (-n_c)): the
// camera turns around what it is focused on. Panning moves the eye and the point looked at
// together, in the camera's own right and up directions; dollying moves them along the view
// direction, and moving (WASD/QE) does the same in the camera's frame.
#include "lfcam/core/lightfield.h"
#include "lfcam/core/slab.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

// Turns the camera around its pivot: `yaw` radians about the camera's up, then `pitch` about its
// right (positive pitch looks up). The focus distance is kept (the pivot stays in focus).
VirtualCameraParams Orbit(const VirtualCameraParams& p, double yaw, double pitch);

// Moves the eye and the point looked at by (right, up, forward) mm in the camera's frame.
VirtualCameraParams Move(const VirtualCameraParams& p, double right_mm, double up_mm,
                         double forward_mm);

// Millimetres on the plane of focus that one pixel of a `width`-pixel frame spans: the drag
// distance that keeps the point under the cursor under it when panning.
double MmPerPixelAtFocus(const VirtualCameraParams& p);

// The view from the array's centre along -n_ca, as `lfcam render` sets it with no flags, keeping
// the frame size and the lens settings.
VirtualCameraParams ResetToArrayCentre(const VirtualCameraParams& p, const ArrayPlane& array);
// The view as the rig's camera at grid position (row, col) (fractional between cameras), in the
// window's frame size: its position, orientation, field of view and principal point, a pinhole
// focused where `p` is (render --as-camera). The light field must record its cameras.
VirtualCameraParams AsRigCamera(const VirtualCameraParams& p, const LightField& lf, double row,
                                double col);

// The view the viewer opens on, framed width x height: the rig's central camera (its centre,
// field of view and principal point: render/rig_camera.h) when the light field records its
// cameras, else the array's centre along -n_ca with the paper's f 500 mm and d_o 4000 mm.
VirtualCameraParams StartingView(const LightField& lf, int width, int height);

// Multiplies the focus distance by `factor`, keeping it beyond the focal length (with breathing).
VirtualCameraParams ScaleFocusDistance(const VirtualCameraParams& p, double factor);

// Multiplies the focal length by `factor` (zoom), keeping it below the focus distance.
VirtualCameraParams ScaleFocalLength(const VirtualCameraParams& p, double factor);

}  // namespace lfcam
