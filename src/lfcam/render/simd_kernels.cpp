// Highway's dynamic dispatch: this file is compiled once per instruction set (foreach_target.h
// includes it again for each), and HWY_DYNAMIC_DISPATCH picks the best the machine supports.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "lfcam/render/simd_kernels.cpp"
#include "lfcam/render/simd_kernels.h"

#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "lfcam/render/sample_rows-inl.h"

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;

// A plane's three functions of p_o for the chunk's pixels.
struct ChunkPoints {
  VF n, x, y;
};

// The functions of one row, at pixel 0 and per pixel, in float.
struct RowAffine {
  float at0, step;
  VF At(const VF& i) const { return hn::MulAdd(hn::Set(DF(), step), i, hn::Set(DF(), at0)); }
};
struct RowPlane {
  RowAffine n, x, y;
  RowPlane(const PlaneAffines& p, int j)
      : n{float(p.n.at00 + p.n.dj * j), float(p.n.di)},
        x{float(p.x.at00 + p.x.dj * j), float(p.x.di)},
        y{float(p.y.at00 + p.y.dj * j), float(p.y.di)} {}
  ChunkPoints At(const VF& i) const { return {n.At(i), x.At(i), y.At(i)}; }
};

// An origin's constants, one per lane (the same in every lane, or gathered per camera).
struct OriginLanes {
  VF num, n_o, x_o, y_o, x0, y0;
  static OriginLanes Broadcast(const OriginConstants& c) {
    const DF d;
    return {hn::Set(d, c.num), hn::Set(d, c.n_o), hn::Set(d, c.x_o),
            hn::Set(d, c.y_o), hn::Set(d, c.x0),  hn::Set(d, c.y0)};
  }
  static OriginLanes Gather(const RaySetup& s, const VI& camera) {
    const DF d;
    return {
        hn::GatherIndex(d, s.cam_num.data(), camera), hn::GatherIndex(d, s.cam_n_o.data(), camera),
        hn::GatherIndex(d, s.cam_x_o.data(), camera), hn::GatherIndex(d, s.cam_y_o.data(), camera),
        hn::GatherIndex(d, s.cam_x0.data(), camera),  hn::GatherIndex(d, s.cam_y0.data(), camera)};
  }
};

// Plane coordinates of the lines from the origin through p_o; `valid` is false where a line
// runs parallel to the plane (its coordinates are then 0, a safe index).
struct PlaneHit {
  VF x, y;
  MF valid;
};
PlaneHit Project(const ChunkPoints& p, const OriginLanes& o) {
  const DF d;
  const VF den = hn::Sub(p.n, o.n_o);
  const MF valid = hn::Ne(den, hn::Zero(d));
  const VF lambda = hn::Div(o.num, hn::IfThenElse(valid, den, hn::Set(d, 1.0f)));
  VF x = hn::MulAdd(lambda, hn::Sub(p.x, o.x_o), o.x0);
  VF y = hn::MulAdd(lambda, hn::Sub(p.y, o.y_o), o.y0);
  // Not a number (an infinite lambda times zero) reads as a miss too.
  const MF finite = hn::And(hn::Eq(x, x), hn::Eq(y, y));
  const MF ok = hn::And(valid, finite);
  return {hn::IfThenElseZero(ok, x), hn::IfThenElseZero(ok, y), ok};
}

// Whether coordinates lie in [-0.5, n - 0.5] along both axes (the window or the st domain).
MF Inside(const PlaneHit& h, int nx, int ny) {
  const DF d;
  const VF lo = hn::Set(d, -0.5f);
  const MF in_x = hn::And(hn::Ge(h.x, lo), hn::Le(h.x, hn::Set(d, float(nx) - 0.5f)));
  const MF in_y = hn::And(hn::Ge(h.y, lo), hn::Le(h.y, hn::Set(d, float(ny) - 0.5f)));
  return hn::And(h.valid, hn::And(in_x, in_y));
}

// Whether st coordinates lie in the sampled domain (the union of the views' windows).
MF InsideDomain(const PlaneHit& h, const RaySetup& s) {
  const DF d;
  const MF in_x =
      hn::And(hn::Ge(h.x, hn::Set(d, s.domain[0])), hn::Le(h.x, hn::Set(d, s.domain[2])));
  const MF in_y =
      hn::And(hn::Ge(h.y, hn::Set(d, s.domain[1])), hn::Le(h.y, hn::Set(d, s.domain[3])));
  return hn::And(h.valid, hn::And(in_x, in_y));
}

// AxisLerp, per lane: x clamped to [0, n - 1], split into i0, the step to i1 (0 or 1) and w1.
struct LerpLanes {
  VI i0, step;
  VF w1;
};
LerpLanes Lerp(const VF& x_in, int n) {
  const DF d;
  const DI di;
  const VF x = hn::Min(hn::Max(x_in, hn::Zero(d)), hn::Set(d, float(n - 1)));
  const VI i0 = hn::Max(hn::Min(hn::ConvertTo(di, x), hn::Set(di, n - 2)), hn::Zero(di));
  const VI i1 = hn::Min(hn::Add(i0, hn::Set(di, 1)), hn::Set(di, n - 1));
  return {i0, hn::Sub(i1, i0), hn::Sub(x, hn::ConvertTo(d, i0))};
}

struct Rgb {
  VF r, g, b;
};

// Decodes one channel (the byte at bit `shift` of each word) through the table.
template <int kShift>
VF Channel(const float* decode, const VI& word) {
  const DF d;
  const DI di;
  return hn::GatherIndex(d, decode, hn::And(hn::ShiftRight<kShift>(word), hn::Set(di, 0xFF)));
}

void AddTap(const RaySetup& s, const VI& offset, const VF& weight, Rgb& acc) {
  // Each sample's R, G, B are the top three bytes of the word that ends at its B byte (the
  // light field guarantees readable bytes before its first sample).
  const VI word =
      hn::GatherOffset(DI(), reinterpret_cast<const std::int32_t*>(s.samples - 1), offset);
  acc.r = hn::MulAdd(weight, Channel<8>(s.decode, word), acc.r);
  acc.g = hn::MulAdd(weight, Channel<16>(s.decode, word), acc.g);
  acc.b = hn::MulAdd(weight, Channel<24>(s.decode, word), acc.b);
}

// acc += w * the bilinear st lookup at (k, l) in the views at byte offsets `view`.
void AddView(const RaySetup& s, const VI& view, const LerpLanes& k, const LerpLanes& l, const VF& w,
             Rgb& acc) {
  const DF d;
  const DI di;
  const int row_bytes = s.n_s * 3;
  const VI o00 =
      hn::Add(view, hn::Add(hn::Mul(l.i0, hn::Set(di, row_bytes)), hn::Mul(k.i0, hn::Set(di, 3))));
  const VI dk = hn::Mul(k.step, hn::Set(di, 3)), dl = hn::Mul(l.step, hn::Set(di, row_bytes));
  const VF one = hn::Set(d, 1.0f);
  const VF wk0 = hn::Sub(one, k.w1), wl0 = hn::Sub(one, l.w1);
  const VF w_l0 = hn::Mul(w, wl0), w_l1 = hn::Mul(w, l.w1);
  AddTap(s, o00, hn::Mul(w_l0, wk0), acc);
  AddTap(s, hn::Add(o00, dk), hn::Mul(w_l0, k.w1), acc);
  AddTap(s, hn::Add(o00, dl), hn::Mul(w_l1, wk0), acc);
  AddTap(s, hn::Add(hn::Add(o00, dl), dk), hn::Mul(w_l1, k.w1), acc);
}

VI ViewOffset(const RaySetup& s, const VI& row, const VI& col) {
  const DI di;
  const VI index = hn::Add(hn::Mul(row, hn::Set(di, s.cols)), col);
  return hn::Mul(index, hn::Set(di, int(s.view_bytes)));
}

// acc += w * camera `index`'s own line through p_o, read bilinearly (the focal-plane read).
// Returns the weight added: w, or (views with their own windows) 0 in the lanes whose line
// leaves the camera's window.
VF AddFocused(const RaySetup& s, const ChunkPoints& st, const VI& index, const OriginLanes& cam,
              const VF& w, Rgb& acc) {
  const PlaneHit h = Project(st, cam);
  const VI view = hn::Mul(index, hn::Set(DI(), int(s.view_bytes)));
  const VF held = s.view_windows ? hn::IfThenElseZero(Inside(h, s.n_s, s.n_t), w) : w;
  AddView(s, view, Lerp(h.x, s.n_s), Lerp(h.y, s.n_t), hn::IfThenElseZero(h.valid, held), acc);
  return held;
}

// As AddFocused, the camera counted by the share of its tent inside its view's window
// (RaySetup::taper): adds and returns w times that share, read clamped to the view's samples.
VF AddFocusedTapered(const RaySetup& s, const ChunkPoints& st, int index, const OriginLanes& cam,
                     const VF& w, Rgb& acc) {
  const PlaneHit h = Project(st, cam);
  const VF share = sample_rows::WindowShare(s, index, h.x, h.y);
  const VF held = hn::IfThenElseZero(h.valid, hn::Mul(w, share));
  if (hn::AllFalse(DF(), hn::Gt(held, hn::Zero(DF())))) return held;  // no lane reads it
  AddView(s, hn::Set(DI(), index * int(s.view_bytes)), Lerp(h.x, s.n_s), Lerp(h.y, s.n_t), held,
          acc);
  return held;
}

// acc += w * the bilinear reads of the four cameras around the lens sample's uv point at the
// ray's own st point (the paper's lookup) or along each camera's own line through p_o (the
// focal-plane lookup), weights wr x wc. Returns the weight added (less than the weights' sum
// only where views have their own windows and a camera's misses the point).
VF AddNearestCameras(const RaySetup& s, bool focal_plane, const ChunkPoints& p_st,
                     const PlaneHit& at_st, const VI rows[2], const VI cols[2], const VF wr[2],
                     const VF wc[2], Rgb& acc) {
  const DF d;
  const DI di;
  VF held = hn::Zero(d);
  if (!focal_plane && !s.view_windows) {
    const LerpLanes k = Lerp(at_st.x, s.n_s), l = Lerp(at_st.y, s.n_t);
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        AddView(s, ViewOffset(s, rows[a], cols[b]), k, l, hn::Mul(wr[a], wc[b]), acc);
    return hn::Add(wr[0], wr[1]);
  }
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      const VI index = hn::Add(hn::Mul(rows[a], hn::Set(di, s.cols)), cols[b]);
      const VF w = hn::Mul(wr[a], wc[b]);
      if (focal_plane) {
        held = hn::Add(held, AddFocused(s, p_st, index, OriginLanes::Gather(s, index), w, acc));
        continue;
      }
      // The view's own samples.
      const PlaneHit local{hn::Sub(at_st.x, hn::GatherIndex(d, s.cam_k_offset.data(), index)),
                           hn::Sub(at_st.y, hn::GatherIndex(d, s.cam_l_offset.data(), index)),
                           at_st.valid};
      const VF w_in = hn::IfThenElseZero(Inside(local, s.n_s, s.n_t), w);
      AddView(s, ViewOffset(s, rows[a], cols[b]), Lerp(local.x, s.n_s), Lerp(local.y, s.n_t), w_in,
              acc);
      held = hn::Add(held, w_in);
    }
  return held;
}

void StoreChunk(const RowOutput& out, int i, const Rgb& acc, const VI& count) {
  const DF d;
  hn::StoreU(acc.r, d, out.r + i);
  hn::StoreU(acc.g, d, out.g + i);
  hn::StoreU(acc.b, d, out.b + i);
  hn::StoreU(count, DI(), out.count + i);
}

}  // namespace

void RenderRowLensSamplesT(const RaySetup& s, bool focal_plane, int j, const RowOutput& out) {
  const DF d;
  const DI di;
  const RowPlane uv(s.uv, j), st(s.st, j);
  const int lanes = int(hn::Lanes(d));
  const int padded = PaddedRowWidth(s.width);
  for (int i = 0; i < padded; i += lanes) {
    const VF pixel = hn::Iota(d, float(i));
    const ChunkPoints p_uv = uv.At(pixel), p_st = st.At(pixel);
    Rgb sum{hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    VI hits = hn::Zero(di);
    for (std::size_t n = 0; n < s.lens_uv.size(); ++n) {
      const PlaneHit at_uv = Project(p_uv, OriginLanes::Broadcast(s.lens_uv[n]));
      const PlaneHit at_st = Project(p_st, OriginLanes::Broadcast(s.lens_st[n]));
      const MF hit = hn::And(Inside(at_uv, s.cols, s.rows), InsideDomain(at_st, s));
      if (hn::AllFalse(d, hit)) continue;
      const LerpLanes c = Lerp(at_uv.x, s.cols), r = Lerp(at_uv.y, s.rows);
      const VF one = hn::Set(d, 1.0f);
      const VF wr[2] = {hn::IfThenElseZero(hit, hn::Sub(one, r.w1)), hn::IfThenElseZero(hit, r.w1)};
      const VF wc[2] = {hn::Sub(one, c.w1), c.w1};
      const VI rows[2] = {r.i0, hn::Add(r.i0, r.step)}, cols[2] = {c.i0, hn::Add(c.i0, c.step)};
      if (!s.view_windows) {
        hits = hn::Add(hits, hn::IfThenElseZero(hn::RebindMask(di, hit), hn::Set(di, 1)));
        AddNearestCameras(s, focal_plane, p_st, at_st, rows, cols, wr, wc, sum);
        continue;
      }
      // Views with their own windows: this lens sample's blend over the cameras that hold its
      // point, renormalised; a sample no camera holds misses.
      Rgb one_sample{hn::Zero(d), hn::Zero(d), hn::Zero(d)};
      const VF held =
          AddNearestCameras(s, focal_plane, p_st, at_st, rows, cols, wr, wc, one_sample);
      const MF read = hn::Gt(held, hn::Zero(d));
      const VF inv = hn::IfThenElseZero(read, hn::Div(one, hn::IfThenElse(read, held, one)));
      sum.r = hn::MulAdd(one_sample.r, inv, sum.r);
      sum.g = hn::MulAdd(one_sample.g, inv, sum.g);
      sum.b = hn::MulAdd(one_sample.b, inv, sum.b);
      hits = hn::Add(hits, hn::IfThenElseZero(hn::RebindMask(di, read), hn::Set(di, 1)));
    }
    const MF any = hn::RebindMask(d, hn::Gt(hits, hn::Zero(di)));
    const VF inv = hn::IfThenElseZero(any, hn::Div(hn::Set(d, 1.0f), hn::ConvertTo(d, hits)));
    StoreChunk(out, i, {hn::Mul(sum.r, inv), hn::Mul(sum.g, inv), hn::Mul(sum.b, inv)}, hits);
  }
}

void RenderRowCamerasT(const RaySetup& s, const GridCameraWeight* uniform, int uniform_count,
                       const float* pixel_weights, const int* cameras, int camera_count, int j,
                       const RowOutput& out) {
  const DF d;
  const DI di;
  const RowPlane st(s.st, j);
  const int lanes = int(hn::Lanes(d));
  const int padded = PaddedRowWidth(s.width);
  for (int i = 0; i < padded; i += lanes) {
    const VF pixel = hn::Iota(d, float(i));
    const ChunkPoints p_st = st.At(pixel);
    Rgb sum{hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    VI reads = hn::Zero(di);
    VF held = hn::Zero(d);  // the weights of the cameras that count
    // Camera `index` in the lanes of `listed` (those whose pixels weigh it): it counts where its
    // own line through p_o meets the sampled st domain and, with views in their own windows, its
    // window holds the point (RenderPixelCameras); with a taper, by its share there.
    const auto read_camera = [&](int index, const VF& w, const MF& listed) {
      const OriginLanes camera = OriginLanes::Broadcast(s.camera_st(index));
      if (s.taper) {
        const VF h = AddFocusedTapered(s, p_st, index, camera, hn::IfThenElseZero(listed, w), sum);
        const MF counted = hn::Gt(h, hn::Zero(d));
        reads = hn::Add(reads, hn::IfThenElseZero(hn::RebindMask(di, counted), hn::Set(di, 1)));
        held = hn::Add(held, h);
        return;
      }
      const MF in = hn::And(listed, InsideDomain(Project(p_st, camera), s));
      if (hn::AllFalse(d, in)) return;
      const VF h = AddFocused(s, p_st, hn::Set(di, index), camera, hn::IfThenElseZero(in, w), sum);
      const MF counted = s.view_windows ? hn::Gt(h, hn::Zero(d)) : in;
      reads = hn::Add(reads, hn::IfThenElseZero(hn::RebindMask(di, counted), hn::Set(di, 1)));
      held = hn::Add(held, h);
    };
    if (uniform_count > 0) {
      const MF all = hn::Lt(pixel, hn::Set(d, float(s.width)));
      for (int n = 0; n < uniform_count; ++n)
        read_camera(uniform[n].row * s.cols + uniform[n].col, hn::Set(d, float(uniform[n].weight)),
                    all);
    } else {
      const int padded_width = PaddedRowWidth(s.width);
      for (int n = 0; n < camera_count; ++n) {
        const int index = cameras[n];
        const VF w = hn::LoadU(d, pixel_weights + std::size_t(index) * padded_width + i);
        const MF listed = hn::Gt(w, hn::Zero(d));
        if (hn::AllFalse(d, listed)) continue;
        read_camera(index, w, listed);
      }
    }
    // The counted cameras' weights renormalised to the whole.
    const MF any = hn::Gt(held, hn::Zero(d));
    const VF scale = hn::IfThenElseZero(
        any, hn::Div(hn::Set(d, 1.0f), hn::IfThenElse(any, held, hn::Set(d, 1.0f))));
    sum = {hn::Mul(sum.r, scale), hn::Mul(sum.g, scale), hn::Mul(sum.b, scale)};
    StoreChunk(out, i, sum, hn::IfThenElseZero(hn::RebindMask(di, any), reads));
  }
}

bool RenderRowCamerasResampledT(const RaySetup& s, const GridCameraWeight* uniform,
                                int uniform_count, const float* pixel_weights, const int* cameras,
                                int camera_count, int j, const RowOutput& out) {
  if (s.view_windows) return false;  // views with their own windows: the per-pixel reads
  const DF d;
  const DI di;
  const int lanes = int(hn::Lanes(d));
  const int padded = PaddedRowWidth(s.width);
  const int count = uniform_count > 0 ? uniform_count : camera_count;
  const auto camera_at = [&](int n) {
    return uniform_count > 0 ? uniform[n].row * s.cols + uniform[n].col : cameras[n];
  };
  // Each camera's sample rows along the pixel row (l is monotonic along it: its ends decide).
  const double last = s.width - 1;
  std::vector<int> first_row(static_cast<std::size_t>(count)), last_row(first_row.size());
  const int top = s.n_t - 1;
  for (int n = 0; n < count; ++n) {
    const OriginConstants c = s.camera_st(camera_at(n));
    double k, l_a, l_b;
    sample_rows::Coordinates(c, s.st, 0, j, &k, &l_a);
    sample_rows::Coordinates(c, s.st, last, j, &k, &l_b);
    const auto row_of = [&](double l) {
      return std::isfinite(l) ? std::clamp(int(std::floor(std::clamp(l, 0.0, double(top)))), 0, top)
                              : -1;
    };
    const int a = row_of(std::min(l_a, l_b)), b = row_of(std::max(l_a, l_b));
    if (a < 0 || b < 0 || b + 1 - a >= kMaxResampledRows) return false;
    first_row[std::size_t(n)] = a;
    last_row[std::size_t(n)] = std::min(b + 1, top);
  }

  std::fill_n(out.r, padded, 0.0f);
  std::fill_n(out.g, padded, 0.0f);
  std::fill_n(out.b, padded, 0.0f);
  // Each camera counts where its own line through p_o meets the sampled st domain (the views
  // share the grid here), or with a taper by its share of its tent inside it; `held` sums the
  // counted cameras' weights, to renormalise by.
  const sample_rows::RowFunctions row(s.st, j);
  std::vector<float> reads(static_cast<std::size_t>(padded), 0.0f), held(reads.size(), 0.0f);
  sample_rows::Planes decoded, resampled;
  sample_rows::TileMap k_map;
  float* const acc[3] = {out.r, out.g, out.b};
  const VF one = hn::Set(d, 1.0f), zero = hn::Zero(d), l_top = hn::Set(d, float(top));
  for (int n = 0; n < count; ++n) {
    const int view_index = camera_at(n);
    const OriginConstants c = s.camera_st(view_index);
    const float* weights =
        uniform_count > 0 ? nullptr : pixel_weights + std::size_t(view_index) * padded;
    const VF uniform_weight = hn::Set(d, uniform_count > 0 ? float(uniform[n].weight) : 0.0f);
    const int l_lo = first_row[std::size_t(n)], l_hi = last_row[std::size_t(n)];
    sample_rows::ComputeMap(c, s.st.n.at(0, j), s.st.n.di, s.st.x.at(0, j), s.st.x.di, s.width,
                            padded, s.n_s, k_map);
    const int k_count = k_map.hi - k_map.lo + 1;
    decoded.Resize(1, std::size_t(k_count + lanes));
    resampled.Resize(std::size_t(l_hi - l_lo + 1), std::size_t(padded));
    const float* const in[3] = {decoded.channel(0, 0), decoded.channel(0, 1),
                                decoded.channel(0, 2)};
    for (int l = l_lo; l <= l_hi; ++l) {
      sample_rows::ReadSampleRow(s, view_index, l, k_map.lo, k_count, l < l_hi,
                                 decoded.channel(0, 0), decoded.channel(0, 1),
                                 decoded.channel(0, 2));
      const std::size_t at = std::size_t(l - l_lo);
      float* const rows_out[3] = {resampled.channel(at, 0), resampled.channel(at, 1),
                                  resampled.channel(at, 2)};
      sample_rows::ResampleRow(k_map, in, rows_out, padded);
    }
    for (int i = 0; i < padded; i += lanes) {
      const VF pixel = hn::Iota(d, float(i));
      const sample_rows::Hit line = sample_rows::Project(c, row, pixel, s.domain);
      VF w = weights ? hn::LoadU(d, weights + i) : uniform_weight;
      auto listed = hn::And(hn::Lt(pixel, hn::Set(d, float(s.width))),
                            weights ? hn::Gt(w, zero) : hn::Ge(w, zero));
      if (s.taper) {
        w = hn::Mul(w, sample_rows::WindowShare(s, view_index, line.k, line.l));
        listed = hn::And(listed, hn::Gt(w, zero));
      }
      const auto read = s.taper ? listed : hn::And(listed, line.inside);
      if (hn::AllFalse(d, read)) continue;
      w = hn::IfThenElseZero(read, w);
      hn::StoreU(hn::Add(hn::LoadU(d, reads.data() + i), hn::IfThenElseZero(read, one)), d,
                 reads.data() + i);
      hn::StoreU(hn::Add(hn::LoadU(d, held.data() + i), w), d, held.data() + i);
      // A tent over the sample rows around each pixel's own l: where the camera's reads span
      // more than three along the row (a camera turned about the vertical), those the read
      // lanes' tents reach.
      const VF lc = hn::Min(hn::Max(line.l, zero), l_top);
      int low = l_lo, high = l_hi;
      if (l_hi - l_lo > 2) {
        const auto read_lanes = hn::RebindMask(di, read);
        const VI rows_of = hn::ConvertTo(di, lc);
        low = std::clamp(
            hn::GetLane(hn::MinOfLanes(di, hn::IfThenElse(read_lanes, rows_of, hn::Set(di, l_hi)))),
            l_lo, l_hi);
        high = std::clamp(hn::GetLane(hn::MaxOfLanes(
                              di, hn::IfThenElse(read_lanes, rows_of, hn::Set(di, l_lo)))) +
                              1,
                          low, l_hi);
      }
      VF sum[3] = {zero, zero, zero};
      for (int l = low; l <= high; ++l) {
        const VF tent = hn::Max(zero, hn::Sub(one, hn::Abs(hn::Sub(lc, hn::Set(d, float(l))))));
        for (int ch = 0; ch < 3; ++ch)
          sum[ch] = hn::MulAdd(tent, hn::LoadU(d, resampled.channel(std::size_t(l - l_lo), ch) + i),
                               sum[ch]);
      }
      for (int ch = 0; ch < 3; ++ch)
        hn::StoreU(hn::MulAdd(w, sum[ch], hn::LoadU(d, acc[ch] + i)), d, acc[ch] + i);
    }
  }
  // The counted cameras' weights renormalised to the whole.
  for (int i = 0; i < padded; ++i) {
    const float h = held[std::size_t(i)];
    const float scale = h > 0 ? 1.0f / h : 0.0f;
    out.r[i] *= scale;
    out.g[i] *= scale;
    out.b[i] *= scale;
    out.count[i] = h > 0 ? std::int32_t(reads[std::size_t(i)]) : 0;
  }
  return true;
}

void InterleaveRowT(const float* r, const float* g, const float* b, int width, float* rgb) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  int i = 0;
  for (; i + lanes <= width; i += lanes)
    hn::StoreInterleaved3(hn::LoadU(d, r + i), hn::LoadU(d, g + i), hn::LoadU(d, b + i), d,
                          rgb + 3 * std::size_t(i));
  for (; i < width; ++i) {
    rgb[3 * std::size_t(i)] = r[i];
    rgb[3 * std::size_t(i) + 1] = g[i];
    rgb[3 * std::size_t(i) + 2] = b[i];
  }
}

const char* TargetNameT() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam {

HWY_EXPORT(RenderRowLensSamplesT);
HWY_EXPORT(RenderRowCamerasT);
HWY_EXPORT(RenderRowCamerasResampledT);
HWY_EXPORT(TargetNameT);
HWY_EXPORT(InterleaveRowT);

void InterleaveRow(const float* r, const float* g, const float* b, int width, float* rgb) {
  HWY_DYNAMIC_DISPATCH(InterleaveRowT)(r, g, b, width, rgb);
}

void RenderRowLensSamples(const RaySetup& setup, bool focal_plane, int j, const RowOutput& out) {
  HWY_DYNAMIC_DISPATCH(RenderRowLensSamplesT)(setup, focal_plane, j, out);
}

void RenderRowCameras(const RaySetup& setup, const GridCameraWeight* uniform, int uniform_count,
                      const float* pixel_weights, const int* cameras, int camera_count, int j,
                      const RowOutput& out) {
  HWY_DYNAMIC_DISPATCH(RenderRowCamerasT)
  (setup, uniform, uniform_count, pixel_weights, cameras, camera_count, j, out);
}

bool RenderRowCamerasResampled(const RaySetup& setup, const GridCameraWeight* uniform,
                               int uniform_count, const float* pixel_weights, const int* cameras,
                               int camera_count, int j, const RowOutput& out) {
  return HWY_DYNAMIC_DISPATCH(RenderRowCamerasResampledT)(
      setup, uniform, uniform_count, pixel_weights, cameras, camera_count, j, out);
}

std::string KernelTargetName() { return HWY_DYNAMIC_DISPATCH(TargetNameT)(); }

}  // namespace lfcam
#endif
