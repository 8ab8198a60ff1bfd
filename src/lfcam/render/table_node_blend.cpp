// Highway's dynamic dispatch, as in simd_kernels.cpp: compiled once per instruction set.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "lfcam/render/table_node_blend.cpp"
#include "lfcam/render/table_node_blend.h"

#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#ifndef LFCAM_RENDER_TABLE_NODE_BLEND_ONCE
#define LFCAM_RENDER_TABLE_NODE_BLEND_ONCE
#include <algorithm>
#endif  // LFCAM_RENDER_TABLE_NODE_BLEND_ONCE

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using DF = hn::ScalableTag<float>;

// One run of one camera: out[i] for i in [i0, i1), the nodes' weights `v` blended.
template <int kNodes>
void BlendRun(const float* v, const float* coefficients, std::size_t coefficient_stride, int i0,
              int i1, float* out) {
  const DF d;
  const int lanes = int(hn::Lanes(d));
  bool any = false;
  for (int n = 0; n < kNodes; ++n) any |= v[n] != 0.0f;
  if (!any) {
    std::fill(out + i0, out + i1, 0.0f);
    return;
  }
  hn::Vec<DF> node[kNodes];
  for (int n = 0; n < kNodes; ++n) node[n] = hn::Set(d, v[n]);
  for (int i = i0; i < i1; i += lanes) {
    // Each product rounded and added in the nodes' order, as the scalar sum does.
    auto sum = hn::Mul(node[0], hn::LoadU(d, coefficients + i));
    for (int n = 1; n < kNodes; ++n)
      sum = hn::Add(sum, hn::Mul(node[n], hn::LoadU(d, coefficients + n * coefficient_stride + i)));
    if (i + lanes <= i1) {
      hn::StoreU(sum, d, out + i);
    } else {
      // The run's last pixels alone: the next run's, or what lies past the row, stay as they
      // are. A masked store where the instruction set has one (x86 from AVX2), else a copy.
#if HWY_TARGET <= HWY_AVX2
      hn::BlendedStore(sum, hn::FirstN(d, std::size_t(i1 - i)), d, out + i);
#else
      HWY_ALIGN float tail[HWY_MAX_BYTES / sizeof(float)];
      hn::Store(sum, d, tail);
      std::copy(tail, tail + (i1 - i), out + i);
#endif
    }
  }
}

template <int kNodes>
void BlendRows(const TableNodeRow& row, float* weights, std::size_t stride) {
  for (int c = 0; c < row.cameras; ++c) {
    if (row.first_run[c] < 0) continue;
    float* out = weights + std::size_t(c) * stride;
    const float* values = row.values + std::size_t(c) * std::size_t(row.runs) * kNodes;
    for (int r = row.first_run[c]; r <= row.last_run[c]; ++r)
      BlendRun<kNodes>(values + std::size_t(r) * kNodes, row.coefficients, row.coefficient_stride,
                       row.run_begin[r], row.run_begin[r + 1], out);
  }
}

void BlendTableNodesT(const TableNodeRow& row, float* weights, std::size_t stride) {
  if (row.nodes == 8)
    BlendRows<8>(row, weights, stride);
  else
    BlendRows<4>(row, weights, stride);
}

}  // namespace
}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam {

HWY_EXPORT(BlendTableNodesT);

void BlendTableNodes(const TableNodeRow& row, float* weights, std::size_t stride) {
  HWY_DYNAMIC_DISPATCH(BlendTableNodesT)(row, weights, stride);
}

}  // namespace lfcam
#endif  // HWY_ONCE
