// Chaining sheet edges into polylines, and the corners of polylines.
#include <numeric>
#include <utility>

#include "sheets/sheet_internal.h"

namespace voxremesh::sheets {

std::vector<Polyline> chainEdges(const ShellEdges& edges, const std::vector<Index>& chosen,
                                 std::size_t pointCount, const std::vector<std::uint8_t>& stop) {
  // The chosen edges at each point, ascending (CSR).
  std::vector<Index> begin(pointCount + 1, 0);
  for (const Index e : chosen) {
    ++begin[edges.edge(e).a + 1];
    ++begin[edges.edge(e).b + 1];
  }
  std::partial_sum(begin.begin(), begin.end(), begin.begin());
  std::vector<Index> at(2 * chosen.size());
  {
    std::vector<Index> fill(begin.begin(), begin.end() - 1);
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      at[fill[edges.edge(chosen[i]).a]++] = Index(i);
      at[fill[edges.edge(chosen[i]).b]++] = Index(i);
    }
  }
  auto degree = [&](Index p) { return begin[p + 1] - begin[p]; };
  auto isStop = [&](Index p) { return degree(p) != 2 || (!stop.empty() && stop[p] != 0); };
  auto other = [&](Index i, Index p) {
    const ShellEdges::Edge& e = edges.edge(chosen[i]);
    return e.a == p ? e.b : e.a;
  };
  // The chosen edge at p (degree 2) other than i.
  auto next = [&](Index p, Index i) { return at[begin[p]] == i ? at[begin[p] + 1] : at[begin[p]]; };

  std::vector<std::uint8_t> used(chosen.size(), 0);
  std::vector<Polyline> result;
  for (Index p = 0; p < pointCount; ++p) {
    if (degree(p) == 0 || !isStop(p)) continue;
    for (Index k = begin[p]; k < begin[p + 1]; ++k) {
      Index i = at[k];
      if (used[i]) continue;
      Polyline line;
      line.points.push_back(p);
      Index q = p;
      for (;;) {
        used[i] = 1;
        q = other(i, q);
        line.points.push_back(q);
        if (isStop(q)) break;
        i = next(q, i);
      }
      result.push_back(std::move(line));
    }
  }
  for (Index start = 0; start < chosen.size(); ++start) {
    if (used[start]) continue;
    Polyline line;
    line.closed = true;
    const Index first = edges.edge(chosen[start]).a;
    Index q = first, i = start;
    for (;;) {
      line.points.push_back(q);
      used[i] = 1;
      q = other(i, q);
      if (q == first) break;
      i = next(q, i);
    }
    result.push_back(std::move(line));
  }
  return result;
}

void appendCorners(const std::vector<Polyline>& polylines, const std::vector<Vec3>& points,
                   double cornerAngleDeg, std::vector<PointIndex>& result) {
  auto turn = [&](PointIndex a, PointIndex b, PointIndex c) {
    const Vec3 &p = points[a], &q = points[b], &r = points[c];
    return angleDeg({q[0] - p[0], q[1] - p[1], q[2] - p[2]},
                    {r[0] - q[0], r[1] - q[1], r[2] - q[2]});
  };
  for (const Polyline& line : polylines) {
    const std::vector<PointIndex>& p = line.points;
    const std::size_t n = p.size();
    if (line.closed) {
      if (n < 3) continue;
      for (std::size_t i = 0; i < n; ++i)
        if (turn(p[(i + n - 1) % n], p[i], p[(i + 1) % n]) > cornerAngleDeg) result.push_back(p[i]);
    } else {
      for (std::size_t i = 1; i + 1 < n; ++i)
        if (turn(p[i - 1], p[i], p[i + 1]) > cornerAngleDeg) result.push_back(p[i]);
    }
  }
}

}  // namespace voxremesh::sheets
