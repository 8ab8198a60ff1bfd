#pragma once
// The virtual camera that stands where one of the rig's cameras stood and records what it
// recorded (`lfcam render --as-camera R,C`): its centre, orientation, image size, focal length
// and principal point (a rectified rig's shifted sensor is an off-axis film, not a toe-in), as
// the light field file records them for each view (format version 3). Between cameras, at a
// fractional grid position, the centre and the principal point are interpolated bilinearly
// between the four cameras around it (for a rectified rig both are linear in the position, so
// this is the camera the rig would have had there); the orientation, image size and focal length
// are the nearest camera's. Lens distortion is not reproduced: the views are stored undistorted.
#include "lfcam/core/lightfield.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

// A pinhole (no breathing: the film stays at f, so any positive focus distance works) focused
// on the st-plane; the caller may then set the aperture and focus. Throws lfcam::Error when the
// light field records no cameras (made before format version 3, or simulated) or (row, col)
// lies outside the grid [0, rows - 1] x [0, cols - 1].
VirtualCameraParams RigCameraParams(const LightField& lf, double row, double col);

// VirtualCameraParams::lens_length_scale for a light field: 1 where its lengths are mm;
// where they are units of its cameras' spacing (WorldLengthUnit "units"), the paper's spacing
// (28 mm) over the array's pitch in those units, so that an aperture of a few units is sampled
// with as many lens samples a camera cell as the paper's array (without it, half the Lytro
// array's width, 4 units, was 1 lens sample: a pinhole).
double LensLengthScale(const LightField& lf);

}  // namespace lfcam
