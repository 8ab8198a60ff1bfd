// The cameras integrator's footprint of a pixel on the uv-plane (CameraIntegratorFrame::
// FootprintOf in C++, which evaluates the same centre and area in a closed form): the lens disk
// projected through the pixel's point in focus p_o onto the array's plane, as the disk of the
// same area. Not a shader of its own: the C++ side puts it
// before the shaders that use it (render_frame.comp's MODE 3, camera_weight_table.comp).
// Positions are relative to the array's corner p_ca.

uniform vec3 focus_at00, focus_di, focus_dj;  // p_o - p_ca at pixel (0, 0), per pixel in i, j
uniform vec3 eye_from_array;                  // e_c - p_ca
uniform vec3 array_u, array_v, array_n;       // u_ca, v_ca, n_ca
uniform vec3 lens_u, lens_v;                  // u_c, v_c
uniform float pitch_mm, lens_radius_mm;

// Pixel's footprint in grid units (camera (col, row) at (col, row)): its centre (x, y) and
// radius (z); false when the lens's lines through p_o run parallel to the array.
bool Footprint(ivec2 pixel, out vec3 footprint) {
  footprint = vec3(0.0);
  const vec3 p_o = focus_at00 + focus_di * float(pixel.x) + focus_dj * float(pixel.y);
  const vec3 to_eye = eye_from_array - p_o;
  const float h_e = dot(array_n, to_eye);
  if (abs(h_e) < 1e-12) return false;
  // U(x) = p_o + lambda(x) (x - p_o), lambda(x) = n.(p_ca - p_o) / n.(x - p_o).
  const float lambda = dot(array_n, -p_o) / h_e;
  const vec3 centre = p_o + lambda * to_eye;
  // The Jacobian of U over the lens disk at its centre, and the disk of the same area.
  const vec3 du = lambda * lens_u - (lambda * dot(array_n, lens_u) / h_e) * to_eye;
  const vec3 dv = lambda * lens_v - (lambda * dot(array_n, lens_v) / h_e) * to_eye;
  const float det = dot(du, array_u) * dot(dv, array_v) - dot(du, array_v) * dot(dv, array_u);
  footprint = vec3(dot(centre, array_u) / pitch_mm - 0.5, dot(centre, array_v) / pitch_mm - 0.5,
                   lens_radius_mm * sqrt(abs(det)) / pitch_mm);
  return true;
}
