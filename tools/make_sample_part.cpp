// make_sample_part: generates the sample part shipped with voxremesh, a hat-section rail (flanges,
// four bends, sloped walls) with three round holes in its top, a one-element hole and a
// two-element slot in its flanges, meshed with quads, as an LS-DYNA keyword deck.
//
// usage: make_sample_part OUT.k [--size H]
//
// The round holes are meshed with O-grids whose outer ring matches the structured grid of the top,
// so the mesh is conforming; every element is oriented with its normal pointing away from the
// inside of the hat.
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "voxremesh/fe_model.h"
#include "voxremesh/io.h"

namespace {

using voxremesh::Id;
using Point2 = std::array<double, 2>;
using Point3 = std::array<double, 3>;

constexpr double kPi = 3.14159265358979323846;

/// The hat profile in the (y, z) plane: flange, bend, wall, bend, top, bend, wall, bend, flange,
/// sampled at about `size` spacing. `topBegin`/`topEnd` receive the index range of the flat top.
std::vector<Point2> hatProfile(double size, std::size_t& topBegin, std::size_t& topEnd) {
  const double flange = 25.0, height = 45.0, top = 60.0, radius = 6.0;
  const double wallAngle = 80.0 * kPi / 180.0;  // wall inclination from horizontal
  std::vector<Point2> points{{0.0, 0.0}};
  double heading = 0.0;  // direction of travel, radians from +y
  auto straight = [&](double length) {
    const int n = std::max(1, static_cast<int>(std::lround(length / size)));
    const Point2 start = points.back();
    for (int k = 1; k <= n; ++k)
      points.push_back({start[0] + length * k / n * std::cos(heading),
                        start[1] + length * k / n * std::sin(heading)});
  };
  auto bend = [&](double turn) {  // turn > 0: counter-clockwise
    const int n = std::max(2, static_cast<int>(std::lround(std::fabs(turn) * radius / size)));
    const double side = turn > 0 ? 1.0 : -1.0;
    const Point2 start = points.back();
    const Point2 centre{start[0] - side * radius * std::sin(heading),
                        start[1] + side * radius * std::cos(heading)};
    const double startAngle = std::atan2(start[1] - centre[1], start[0] - centre[0]);
    for (int k = 1; k <= n; ++k) {
      const double a = startAngle + turn * k / n;
      points.push_back({centre[0] + radius * std::cos(a), centre[1] + radius * std::sin(a)});
    }
    heading += turn;
  };
  const double wall = height / std::sin(wallAngle) - 2.0 * radius * std::tan(wallAngle / 2.0);
  straight(flange);
  bend(wallAngle);
  straight(wall);
  bend(-wallAngle);
  topBegin = points.size() - 1;
  straight(top);
  topEnd = points.size() - 1;
  bend(-wallAngle);
  straight(wall);
  bend(wallAngle);
  straight(flange);
  return points;
}

struct Generator {
  voxremesh::FeModel model;
  Id nextNode = 1000001;
  Id nextShell = 2000001;
  static constexpr Id kPart = 100;

  Id addNode(const Point3& p) {
    model.nodes.push_back({nextNode, p});
    return nextNode++;
  }

  /// Adds a quad, flipped if needed so that its normal points along `up`.
  void addQuad(std::array<Id, 4> ids, const std::array<Point3, 4>& p, const Point3& up) {
    const Point3 d1{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const Point3 d2{p[3][0] - p[1][0], p[3][1] - p[1][1], p[3][2] - p[1][2]};
    const Point3 n{d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                   d1[0] * d2[1] - d1[1] * d2[0]};
    if (n[0] * up[0] + n[1] * up[1] + n[2] * up[2] < 0) std::swap(ids[1], ids[3]);
    voxremesh::Shell shell;
    shell.id = nextShell++;
    shell.part = kPart;
    shell.nodes = ids;
    shell.nodeCount = 4;
    model.shells.push_back(shell);
  }
};

voxremesh::FeModel makeHatRail(double size) {
  std::size_t topBegin = 0, topEnd = 0;
  const std::vector<Point2> profile = hatProfile(size, topBegin, topEnd);
  const double length = 400.0;
  const int nx = static_cast<int>(std::lround(length / size));
  const std::size_t ny = profile.size();

  // Round holes: square patches of k x k top elements replaced by O-grids.
  const int k = std::max(2, static_cast<int>(std::lround(24.0 / size)));
  const int topCells = static_cast<int>(topEnd - topBegin);
  const int j0 = static_cast<int>(topBegin) + (topCells - k) / 2;
  const std::vector<int> holeStarts{nx / 4 - k / 2, nx / 2 - k / 2, 3 * nx / 4 - k / 2};
  auto inHolePatch = [&](int i, int j) {  // cell (i, j) lies in a hole patch
    for (int i0 : holeStarts)
      if (i >= i0 && i < i0 + k && j >= j0 && j < j0 + k) return true;
    return false;
  };
  auto nodeInsidePatch = [&](int i, int j) {  // grid node strictly inside a patch
    for (int i0 : holeStarts)
      if (i > i0 && i < i0 + k && j > j0 && j < j0 + k) return true;
    return false;
  };
  // Small holes in the flanges: one element on the left, a two-element slot on the right.
  auto inSmallHole = [&](int i, int j) {
    return (i == nx / 3 && j == 1) ||
           ((i == 2 * nx / 3 || i == 2 * nx / 3 + 1) && j == static_cast<int>(ny) - 3);
  };

  Generator g;
  std::vector<Id> grid(static_cast<std::size_t>(nx + 1) * ny, 0);
  auto gridId = [&](int i, int j) -> Id& { return grid[static_cast<std::size_t>(i) * ny + j]; };
  auto position = [&](int i, int j) {
    return Point3{length * i / nx, profile[j][0], profile[j][1]};
  };
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j < static_cast<int>(ny); ++j)
      if (!nodeInsidePatch(i, j)) gridId(i, j) = g.addNode(position(i, j));

  // The outward side of the profile: left of the direction of travel (+z on the top).
  auto upAt = [&](int j) {
    const int a = std::max(0, j - 1), b = std::min(static_cast<int>(ny) - 1, j + 1);
    const double dy = profile[b][0] - profile[a][0], dz = profile[b][1] - profile[a][1];
    return Point3{0.0, -dz, dy};
  };
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j + 1 < static_cast<int>(ny); ++j) {
      if (inHolePatch(i, j) || inSmallHole(i, j)) continue;
      g.addQuad({gridId(i, j), gridId(i + 1, j), gridId(i + 1, j + 1), gridId(i, j + 1)},
                {position(i, j), position(i + 1, j), position(i + 1, j + 1), position(i, j + 1)},
                upAt(j));
    }

  // O-grid of each round hole: the patch boundary ring (4k nodes) to a circle, `layers` quads deep.
  const int layers = std::max(2, k / 2);
  for (int i0 : holeStarts) {
    std::vector<std::pair<int, int>> ring;  // patch boundary nodes, counter-clockwise
    for (int t = 0; t < k; ++t) ring.push_back({i0 + t, j0});
    for (int t = 0; t < k; ++t) ring.push_back({i0 + k, j0 + t});
    for (int t = 0; t < k; ++t) ring.push_back({i0 + k - t, j0 + k});
    for (int t = 0; t < k; ++t) ring.push_back({i0, j0 + k - t});
    const Point3 corner = position(i0, j0), opposite = position(i0 + k, j0 + k);
    const Point3 centre{(corner[0] + opposite[0]) / 2, (corner[1] + opposite[1]) / 2, corner[2]};
    const double radius = 0.3 * (opposite[0] - corner[0]);
    const std::size_t n = ring.size();
    std::vector<std::vector<Id>> rings(layers + 1, std::vector<Id>(n));
    std::vector<std::vector<Point3>> points(layers + 1, std::vector<Point3>(n));
    for (std::size_t r = 0; r < n; ++r) {
      const Point3 outer = position(ring[r].first, ring[r].second);
      const double angle = std::atan2(outer[1] - centre[1], outer[0] - centre[0]);
      const Point3 inner{centre[0] + radius * std::cos(angle), centre[1] + radius * std::sin(angle),
                         centre[2]};
      for (int l = 0; l <= layers; ++l) {
        const double s = static_cast<double>(l) / layers;  // 0: circle, 1: patch boundary
        points[l][r] = {inner[0] + s * (outer[0] - inner[0]), inner[1] + s * (outer[1] - inner[1]),
                        centre[2]};
        rings[l][r] = l == layers ? gridId(ring[r].first, ring[r].second) : g.addNode(points[l][r]);
      }
    }
    for (int l = 0; l < layers; ++l)
      for (std::size_t r = 0; r < n; ++r) {
        const std::size_t q = (r + 1) % n;
        g.addQuad({rings[l][r], rings[l][q], rings[l + 1][q], rings[l + 1][r]},
                  {points[l][r], points[l][q], points[l + 1][q], points[l + 1][r]},
                  Point3{0.0, 0.0, 1.0});
      }
  }

  voxremesh::FeModel& model = g.model;
  model.sourceFormat = voxremesh::DeckFormat::LsDyna;
  model.parts.push_back({Generator::kPart, "Hat rail", true});
  auto verbatim = [&](const std::string& text) {
    model.blocks.push_back({voxremesh::DeckBlock::Kind::Verbatim, text});
  };
  verbatim(
      "$ Sample part for voxremesh: a hat-section rail, 400 mm long, with flanges, four bends,\n"
      "$ three round holes in the top, a one-element hole and a two-element slot in the flanges.\n"
      "$ Generated by tools/make_sample_part (units: mm, t, s, N).\n"
      "*KEYWORD\n*TITLE\nvoxremesh sample: hat-section rail\n");
  verbatim(
      "*PART\n$# title\nHat rail\n"
      "$#     pid     secid       mid     eosid      hgid      grav    adpopt      tmid\n"
      "       100         1         1         0         0         0         0         0\n");
  verbatim(
      "*SECTION_SHELL\n"
      "$#   secid    elform      shrf       nip     propt   qr/irid     icomp     setyp\n"
      "         1        16  0.833333         5         0         0         0         1\n"
      "$#      t1        t2        t3        t4      nloc     marea      idof    edgset\n"
      "       1.5       1.5       1.5       1.5       0.0       0.0       0.0         0\n");
  verbatim(
      "*MAT_ELASTIC\n"
      "$#     mid        ro         e        pr\n"
      "         1   7.85e-9  210000.0       0.3\n");
  model.blocks.push_back({voxremesh::DeckBlock::Kind::Nodes, {}});
  model.blocks.push_back({voxremesh::DeckBlock::Kind::Shells, {}});
  verbatim("*END\n");
  return model;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: make_sample_part OUT.k [--size H]\n");
    return 2;
  }
  double size = 5.0;
  for (int a = 2; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--size" && a + 1 < argc) {
      size = std::stod(argv[++a]);
    } else {
      std::fprintf(stderr, "make_sample_part: unknown option '%s'\n", arg.c_str());
      return 2;
    }
  }
  if (!(size >= 0.5 && size <= 20.0)) {
    std::fprintf(stderr, "make_sample_part: --size must be between 0.5 and 20 mm\n");
    return 2;
  }
  try {
    const voxremesh::FeModel model = makeHatRail(size);
    voxremesh::writeDeck(model, argv[1]);
    std::printf("wrote %s: %zu nodes, %zu quads\n", argv[1], model.nodes.size(),
                model.shells.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_sample_part: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
