#include "lfcam/core/slab.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"

namespace lfcam {

std::optional<SlabCoords> Slab::intersect(const Ray& ray) const {
  const auto t_uv = Plane{uv.p_ca, uv.n_ca}.intersect(ray);
  const auto t_st = Plane{st.origin, st.normal()}.intersect(ray);
  if (!t_uv || !t_st) return std::nullopt;
  const Vec3 x_uv = ray.at(*t_uv) - uv.p_ca;
  const Vec3 x_st = ray.at(*t_st) - st.origin;
  return SlabCoords{x_uv.dot(uv.u_ca) / uv.width_mm(), x_uv.dot(uv.v_ca) / uv.height_mm(),
                    x_st.dot(st.x_axis) / st.width_mm, x_st.dot(st.y_axis) / st.height_mm};
}

namespace {

void RequireUnit(const Vec3& v, const char* name) {
  if (!v.allFinite() || std::abs(v.norm() - 1.0) > 1e-6)
    throw Error(fmt::format("slab: {} must be a finite unit vector (norm {})", name, v.norm()));
}

void RequireOrthogonal(const Vec3& a, const Vec3& b, const char* names) {
  if (std::abs(a.dot(b)) > 1e-6) throw Error(fmt::format("slab: {} must be orthogonal", names));
}

}  // namespace

namespace {

// Geometry beyond these is a corrupt file, not a camera array: positions within 1000 km, sizes
// from a micrometre to 1000 km, st domains within 1000 view windows of the board.
constexpr double kMaxCoordinateMm = 1e9, kMinSizeMm = 1e-3, kMaxStDomain = kMaxStDomainBound;

void RequireBounded(const Vec3& p, const char* name) {
  if (!p.allFinite() || p.cwiseAbs().maxCoeff() > kMaxCoordinateMm)
    throw Error(fmt::format("slab: {} must be finite and within {} mm of the origin", name,
                            kMaxCoordinateMm));
}

void RequireSize(double mm, const char* name) {
  if (!(mm >= kMinSizeMm && mm <= kMaxCoordinateMm))
    throw Error(fmt::format("slab: {} {} mm must be between {} and {} mm", name, mm, kMinSizeMm,
                            kMaxCoordinateMm));
}

}  // namespace

void Slab::validate() const {
  RequireBounded(uv.p_ca, "p_ca");
  RequireBounded(st.origin, "view window origin");
  RequireSize(uv.pitch_mm, "pitch_mm");
  RequireSize(st.width_mm, "view window width");
  RequireSize(st.height_mm, "view window height");
  for (const double x : {st_domain.s0, st_domain.s1, st_domain.t0, st_domain.t1})
    if (!(std::abs(x) <= kMaxStDomain))
      throw Error(fmt::format("slab: st domain bound {} is outside -{}..{}", x, kMaxStDomain,
                              kMaxStDomain));
  RequireUnit(uv.u_ca, "u_ca");
  RequireUnit(uv.v_ca, "v_ca");
  RequireUnit(uv.n_ca, "n_ca");
  RequireOrthogonal(uv.u_ca, uv.v_ca, "u_ca and v_ca");
  RequireOrthogonal(uv.u_ca, uv.n_ca, "u_ca and n_ca");
  RequireOrthogonal(uv.v_ca, uv.n_ca, "v_ca and n_ca");
  if (uv.u_ca.cross(uv.v_ca).dot(uv.n_ca) < 0)
    throw Error("slab: (u_ca, v_ca, n_ca) must be right-handed");
  if (!uv.p_ca.allFinite()) throw Error("slab: p_ca must be finite");
  if (uv.rows < 1 || uv.cols < 1 || uv.rows > kMaxViewsPerSide || uv.cols > kMaxViewsPerSide)
    throw Error(fmt::format("slab: array grid {}x{} is out of range", uv.rows, uv.cols));
  if (!(uv.pitch_mm > 0) || !std::isfinite(uv.pitch_mm))
    throw Error("slab: pitch_mm must be positive");
  RequireUnit(st.x_axis, "view window x axis");
  RequireUnit(st.y_axis, "view window y axis");
  RequireOrthogonal(st.x_axis, st.y_axis, "view window axes");
  if (!st.origin.allFinite()) throw Error("slab: view window origin must be finite");
  if (!(st.width_mm > 0) || !(st.height_mm > 0) || !std::isfinite(st.width_mm) ||
      !std::isfinite(st.height_mm))
    throw Error("slab: view window size must be positive");
  if (!(st_domain.s1 > st_domain.s0) || !(st_domain.t1 > st_domain.t0) ||
      !std::isfinite(st_domain.s0 + st_domain.s1 + st_domain.t0 + st_domain.t1))
    throw Error("slab: st domain must have s1 > s0 and t1 > t0");
  if (std::abs(separation_mm()) < 1e-6) throw Error("slab: uv- and st-planes coincide");
}

void to_json(nlohmann::json& j, const Slab& slab) {
  auto v3 = [](const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  j = nlohmann::json{
      {"p_ca", v3(slab.uv.p_ca)},
      {"u_ca", v3(slab.uv.u_ca)},
      {"v_ca", v3(slab.uv.v_ca)},
      {"n_ca", v3(slab.uv.n_ca)},
      {"rows", slab.uv.rows},
      {"cols", slab.uv.cols},
      {"pitch_mm", slab.uv.pitch_mm},
      {"view_window",
       {{"origin", v3(slab.st.origin)},
        {"x_axis", v3(slab.st.x_axis)},
        {"y_axis", v3(slab.st.y_axis)},
        {"width_mm", slab.st.width_mm},
        {"height_mm", slab.st.height_mm}}},
      {"st_domain", nlohmann::json::array({slab.st_domain.s0, slab.st_domain.t0, slab.st_domain.s1,
                                           slab.st_domain.t1})},
  };
}

void from_json(const nlohmann::json& j, Slab& slab) {
  const std::string where = "slab";
  slab.uv.p_ca = JsonVec3(j, "p_ca", where);
  slab.uv.u_ca = JsonVec3(j, "u_ca", where);
  slab.uv.v_ca = JsonVec3(j, "v_ca", where);
  slab.uv.n_ca = JsonVec3(j, "n_ca", where);
  slab.uv.rows = int(JsonInteger(j, "rows", 1, kMaxViewsPerSide, where));
  slab.uv.cols = int(JsonInteger(j, "cols", 1, kMaxViewsPerSide, where));
  slab.uv.pitch_mm = JsonNumber(j, "pitch_mm", where);
  const auto& w = JsonField(j, "view_window", "slab");
  const std::string window = "slab: view_window";
  slab.st.origin = JsonVec3(w, "origin", window);
  slab.st.x_axis = JsonVec3(w, "x_axis", window);
  slab.st.y_axis = JsonVec3(w, "y_axis", window);
  slab.st.width_mm = JsonNumber(w, "width_mm", window);
  slab.st.height_mm = JsonNumber(w, "height_mm", window);
  const auto& d = JsonField(j, "st_domain", where);
  if (!d.is_array() || d.size() != 4) throw Error("slab: st_domain must be [s0, t0, s1, t1]");
  const std::string domain = "slab: st_domain";
  slab.st_domain = {JsonNumber(d[0], "", domain), JsonNumber(d[1], "", domain),
                    JsonNumber(d[2], "", domain), JsonNumber(d[3], "", domain)};
  slab.validate();
}

}  // namespace lfcam
