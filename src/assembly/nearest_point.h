// Nearest-point queries on a fixed point set: a uniform grid of cells (about one point per
// cell) searched in growing shells of cells. Internal to src/assembly.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace voxremesh::assembly {

/// Answers "which of these points is nearest to q" for many queries.
class NearestPoint {
 public:
  /// Indexes the points (kept by reference: they must outlive this object and not change).
  /// Preconditions: coordinates finite.
  explicit NearestPoint(const std::vector<std::array<double, 3>>& points);

  /// The index of the point nearest to q (ties: the lower index) and its distance; index
  /// SIZE_MAX when there are no points.
  std::size_t nearest(const std::array<double, 3>& q, double* distance = nullptr) const;

 private:
  std::array<std::int64_t, 3> cellOf(const std::array<double, 3>& p) const;
  std::size_t cellIndex(std::int64_t i, std::int64_t j, std::int64_t k) const;

  const std::vector<std::array<double, 3>>& points_;
  std::array<double, 3> origin_{};
  double cell_ = 1.0;
  std::array<std::int64_t, 3> dims_{1, 1, 1};
  std::vector<std::uint32_t> cellStart_;  ///< prefix sums of the points per cell
  std::vector<std::uint32_t> order_;      ///< point indices sorted by cell, then index
};

}  // namespace voxremesh::assembly
