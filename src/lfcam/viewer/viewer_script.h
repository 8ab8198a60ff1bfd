#pragma once
// `lfcam view --script FILE`: what a person would do, one command a line, for tests and
// demonstrations (docs/viewer.md). Blank lines and lines starting with # are skipped.
//
//   window W H                 resize the window (screen pixels)
//   set NAME VALUE             a parameter: focal-length, focus-distance, aperture, lens-rate
//                              (numbers, mm), breathing (on|off), integrator (lens-samples|
//                              cameras), interpolation (quadrilinear|focal-plane), scale
//                              (render scale, 0.05..2), eye|look-at|up (X,Y,Z)
//   camera R C                 stand as the rig's camera at grid row R, column C (fractional
//                              between cameras; a light field that records its cameras)
//   click X Y                  click to focus at window pixel (X, Y), top-left origin
//   drag X0 Y0 X1 Y1 [BUTTON]  drag with left (orbit), middle (pan) or right; shift-left pans
//   key NAME                   press a key (F1, F2, F3, F12, W, A, S, D, Q, E, R, ...)
//   wait                       until the frame is at full quality for the current view
//   frames N                   draw N frames
//   screenshot PATH.png        save the frame (full quality) and PATH.json, its view
//   capture PATH.png           save the window as it shows, the control windows included
//   print                      print the view as JSON on standard output (with a video: the
//                              frame shown, the frame count, whether it plays)
//   play / pause               a light field video plays from the playhead, or stops
//   seek K                     to frame K (from 0)
//   step N                     N frames on (negative: back); pauses
//   loop on|off                play on from the start at the end, or stop there
//   wait-frame K               until frame K is on screen (while playing: drawn at any scale)
//   quit
#include <string>
#include <vector>

namespace lfcam {

struct ScriptCommand {
  std::string name;               // window, set, click, drag, key, wait, frames, screenshot, ...
  std::vector<std::string> args;  // as written
  int line = 0;
};

// Reads and checks a script (every command known, with the right number of arguments and
// numbers where numbers belong); throws lfcam::Error naming the file and line.
std::vector<ScriptCommand> ReadViewerScript(const std::string& path);
std::vector<ScriptCommand> ParseViewerScript(const std::string& text, const std::string& where);

}  // namespace lfcam
