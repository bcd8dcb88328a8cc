#include "surface_nbv/sim/procedural_scenes.h"

#include <algorithm>
#include <array>
#include <utility>
#include <cmath>

#include <Eigen/Geometry>

#include "surface_nbv/sim/mesh_builder.h"

namespace surface_nbv {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr int kSegments = 32;

Vector3d at(const Vector2d& p, double z) { return Vector3d(p.x(), p.y(), z); }

// Axis-aligned box given by its x, y and z ranges.
void slab(MeshBuilder& b, double x0, double x1, double y0, double y1, double z0, double z1) {
  b.addAlignedBox(Vector3d(x0, y0, z0), Vector3d(x1, y1, z1));
}

// A square centred at the origin with each corner cut by a notch (re-entrant
// when `reentrant`, a 45 degree chamfer otherwise), counter-clockwise.
std::vector<Vector2d> notchedSquare(double half, double cut, bool reentrant) {
  const double i = half - cut;
  std::vector<Vector2d> quarter = {{i, -half}, {half, -i}};
  if (reentrant) quarter.insert(quarter.begin() + 1, Vector2d(i, -i));
  std::vector<Vector2d> out;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Rotation2Dd rot(0.5 * M_PI * k);
    for (const Vector2d& p : quarter) out.push_back(rot * p);
  }
  return out;
}

std::vector<Vector2d> regularPolygon(double radius, int sides) {
  std::vector<Vector2d> out;
  for (int k = 0; k < sides; ++k) {
    const double t = 2.0 * M_PI * (k + 0.5) / sides;
    out.emplace_back(radius * std::cos(t), radius * std::sin(t));
  }
  return out;
}

void buildBox(MeshBuilder& b) { b.addBox(Vector3d(0, 0, 2), Vector3d(4, 4, 4)); }

void buildSphere(MeshBuilder& b) { b.addSphere(Vector3d(0, 0, 2), 2.0, 32, 64); }

void buildRoom(MeshBuilder& b) {
  b.setInward(true);
  slab(b, -5, 5, -4, 4, 0, 4);
  b.setInward(false);
  slab(b, 1.5, 2.5, 0.5, 1.5, 0, 4);
}

// ---- plant: x in [-32.5, 32.5], y in [-21, 21], z in [0, 15] ----

// An elevated walkway at deck height z from `from` to `to`: two girders, a
// grating deck, handrails on stanchions, and `spans - 1` pairs of posts.
void addWalkway(MeshBuilder& b, const Vector2d& from, const Vector2d& to, double z, int spans) {
  const Vector2d d = (to - from).normalized();
  const Vector2d n(-d.y(), d.x());
  b.addBeam(at(from, z + 0.19), at(to, z + 0.19), 1.5, 0.08);
  const int stanchions = static_cast<int>(std::ceil((to - from).norm() / 2.5));
  for (double s : {-1.0, 1.0}) {
    b.addBeam(at(from + 0.6 * s * n, z), at(to + 0.6 * s * n, z), 0.3, 0.3);
    b.addBeam(at(from + 0.7 * s * n, z + 1.25), at(to + 0.7 * s * n, z + 1.25), 0.08, 0.08);
    for (int i = 0; i <= stanchions; ++i) {
      const Vector2d p = from + (to - from) * (double(i) / stanchions) + 0.7 * s * n;
      b.addBeam(at(p, z + 0.23), at(p, z + 1.29), 0.08, 0.08);
    }
  }
  for (int i = 1; i < spans; ++i) {
    const Vector2d p = from + (to - from) * (double(i) / spans);
    b.addBeam(at(p - 0.6 * n, 0.0), at(p - 0.6 * n, z - 0.15), 0.3, 0.3);
    b.addBeam(at(p + 0.6 * n, 0.0), at(p + 0.6 * n, z - 0.15), 0.3, 0.3);
    b.addBeam(at(p - 0.75 * n, z - 0.3), at(p + 0.75 * n, z - 0.3), 0.2, 0.2);
  }
}

// Main hall: x in [-32.5, 7.5], y in [-4, 16], 0.4 m walls, roof at 11.7-12 m,
// a 6 x 7 m door in the east wall and a 5 x 6 m door in the south wall.
void addHall(MeshBuilder& b) {
  const double x0 = -32.5, x1 = 7.5, y0 = -4.0, y1 = 16.0, t = 0.4, h = 11.7;
  slab(b, x0, x0 + t, y0, y1, 0, h);
  slab(b, x0, x1, y1 - t, y1, 0, h);
  slab(b, x1 - t, x1, y0, 3.0, 0, h);
  slab(b, x1 - t, x1, 9.0, y1, 0, h);
  slab(b, x1 - t, x1, 3.0, 9.0, 7.0, h);
  slab(b, x0, -12.0, y0, y0 + t, 0, h);
  slab(b, -7.0, x1, y0, y0 + t, 0, h);
  slab(b, -12.0, -7.0, y0, y0 + t, 6.0, h);
  slab(b, x0, x1, y0, y1, h, 12.0);
  slab(b, -28.0, 3.0, 4.0, 8.0, 12.0, 13.0);
  // Crane runway on columns along the long walls, and one crane bridge.
  for (double y : {y0 + t + 0.2, y1 - t - 0.2}) {
    for (double x : {-24.0, -16.0, -4.0, 4.0}) slab(b, x - 0.2, x + 0.2, y - 0.2, y + 0.2, 0, 9);
    b.addBeam(Vector3d(x0 + t, y, 9.15), Vector3d(x1 - t, y, 9.15), 0.4, 0.3);
  }
  b.addBeam(Vector3d(-10.0, y0 + t + 0.2, 9.7), Vector3d(-10.0, y1 - t - 0.2, 9.7), 0.6, 0.8);
  // Machinery: a turbine block with a generator, and a control cabinet row.
  slab(b, -27.0, -17.0, 4.0, 8.0, 0, 3.5);
  slab(b, -17.0, -13.0, 5.0, 7.0, 0, 0.6);
  b.addCylinder(Vector3d(-17.0, 6.0, 2.0), Vector3d(-13.0, 6.0, 2.0), 1.6, kSegments);
  slab(b, -5.0, 1.0, 9.5, 12.5, 0, 3.0);
}

// Five equal 2 m flues reaching 15 m at x = 27, braced together, each ducted
// to a raised collector duct along the east edge (x up to 32.5).
void addFlues(MeshBuilder& b) {
  for (int k = -2; k <= 2; ++k) {
    const double y = 6.0 * k;
    slab(b, 25.5, 28.5, y - 1.5, y + 1.5, 0, 1.0);
    b.addCylinder(Vector3d(27, y, 0), Vector3d(27, y, 15), 1.0, kSegments);
    b.addCylinder(Vector3d(27, y, 14.2), Vector3d(27, y, 14.6), 1.15, kSegments);
    slab(b, 27.0, 30.5, y - 0.6, y + 0.6, 3.8, 5.2);
    slab(b, 31.3, 31.7, y - 0.2, y + 0.2, 0, 3.0);
  }
  slab(b, 30.5, 32.5, -14.0, 14.0, 3.0, 6.0);
  b.addBeam(Vector3d(27, -12, 10.5), Vector3d(27, 12, 10.5), 0.4, 0.5);
}

// Two vertical tanks in a low bund, a horizontal tank on saddles with pumps,
// a narrow 2.8 m passage along the south edge with pipes over it, containers
// and a substation along the north edge.
void addYard(MeshBuilder& b) {
  for (double x : {12.0, 20.0}) {
    b.addCylinder(Vector3d(x, -13, 0), Vector3d(x, -13, 8), 2.5, kSegments);
    b.addFrustum(Vector3d(x, -13, 8), Vector3d(x, -13, 9), 2.5, 0.6, kSegments);
    b.addCylinder(Vector3d(x, -13, 9), Vector3d(x, -13, 9.4), 0.4, 16);
  }
  slab(b, 8.5, 23.5, -16.8, -16.5, 0, 1);
  slab(b, 8.5, 23.5, -9.5, -9.2, 0, 1);
  slab(b, 8.5, 8.8, -16.8, -9.2, 0, 1);
  slab(b, 23.2, 23.5, -16.8, -9.2, 0, 1);

  b.addCylinder(Vector3d(-28, -10.5, 2.2), Vector3d(-18, -10.5, 2.2), 1.6, kSegments);
  b.addSphere(Vector3d(-28, -10.5, 2.2), 1.6, 12, 24);
  b.addSphere(Vector3d(-18, -10.5, 2.2), 1.6, 12, 24);
  for (double x : {-26.0, -20.0}) b.addBox(Vector3d(x, -10.5, 0.7), Vector3d(0.6, 2.4, 1.4));
  for (double x : {-13.0, -10.0}) {
    slab(b, x - 1.0, x + 1.0, -11.0, -9.8, 0, 1.2);
    b.addCylinder(Vector3d(x, -10.4, 1.2), Vector3d(x, -10.4, 3.0), 0.15, 12);
  }
  b.addCylinder(Vector3d(-16.4, -10.4, 3.0), Vector3d(-10.0, -10.4, 3.0), 0.15, 12);

  slab(b, -30.0, 2.0, -21.0, -20.6, 0, 5);
  slab(b, -30.0, 2.0, -17.8, -17.4, 0, 5);
  for (double x : {-14.0, -13.4}) {
    b.addCylinder(Vector3d(x, -21, 5.25), Vector3d(x, -4, 5.25), 0.25, 16);
  }
  slab(b, -14.3, -13.1, -4.4, -4.0, 4.8, 5.6);

  for (double x : {-26.0, -19.0, -12.0}) slab(b, x - 3.03, x + 3.03, 18.56, 21.0, 0, 2.59);
  slab(b, -22.03, -15.97, 18.56, 21.0, 2.59, 5.18);
  slab(b, 11.0, 17.0, 16.5, 21.0, 0, 4.5);
  b.addBox(Vector3d(12.5, 14.0, 1.2), Vector3d(2.2, 1.6, 2.4));
  b.addBox(Vector3d(15.5, 14.0, 1.2), Vector3d(2.2, 1.6, 2.4));
}

void buildPlant(MeshBuilder& b) {
  addHall(b);
  addFlues(b);
  addWalkway(b, Vector2d(7.5, 12), Vector2d(26.0, 12), 8.0, 3);
  addWalkway(b, Vector2d(7.5, 0), Vector2d(26.0, 0), 10.0, 3);
  addWalkway(b, Vector2d(7.5, -2.5), Vector2d(26.1, -6.0), 6.0, 3);
  addYard(b);
}

// ---- statue: x, y in [-10, 10], z in [0, 60], facing -y ----

void addPedestal(MeshBuilder& b) {
  slab(b, -10, 10, -10, 10, 0, 2);
  slab(b, -8.5, 8.5, -8.5, 8.5, 2, 3.5);
  b.addPrism(notchedSquare(7.0, 1.5, true), 3.5, 17.0);
  for (int k = 0; k < 4; ++k) {
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.5 * M_PI * k, Vector3d::UnitZ()).matrix();
    for (double s : {-3.0, 3.0}) {
      b.addOrientedBox(rot * Vector3d(7.2, s, 10.25), Vector3d(0.2, 0.6, 6.75), rot);
    }
  }
  slab(b, -8, 8, -8, 8, 17, 18.2);
  b.addPrism(notchedSquare(6.2, 1.2, false), 18.2, 22.0);
  slab(b, -6.8, 6.8, -6.8, 6.8, 22, 23.2);
  slab(b, -5.5, 5.5, -5.5, 5.5, 23.2, 25);
  b.addPrism(regularPolygon(4.6, 8), 25, 26);
}

// A bent limb: two beams with spheres filling the joints.
void addLimb(MeshBuilder& b, const Vector3d& shoulder, const Vector3d& elbow,
             const Vector3d& hand, double thickness) {
  b.addBeam(shoulder, elbow, thickness, thickness);
  b.addBeam(elbow, hand, thickness, thickness);
  for (const Vector3d& joint : {shoulder, elbow, hand}) b.addSphere(joint, 0.6 * thickness, 8, 16);
}

void addFigure(MeshBuilder& b) {
  b.addFrustum(Vector3d(0, 0, 26), Vector3d(0, 0, 44), 4.2, 2.6, kSegments);
  b.addFrustum(Vector3d(0.9, -0.9, 26), Vector3d(0.4, -0.6, 41), 2.6, 1.4, 24);
  b.addFrustum(Vector3d(0, 0, 44), Vector3d(0, 0, 46.4), 2.6, 2.1, kSegments);
  b.addBox(Vector3d(0, 0, 45.8), Vector3d(6.0, 2.6, 1.4));
  b.addCylinder(Vector3d(0, 0, 46.4), Vector3d(0, 0, 48.6), 0.8, 24);
  b.addSphere(Vector3d(0, 0, 50.2), 1.8, 16, kSegments);
  b.addFrustum(Vector3d(0, 0, 50.9), Vector3d(0, 0, 51.7), 1.9, 1.75, kSegments);
  // Seven crown rays over the front half, tilted 35 degrees up.
  const double tilt = 35.0 * M_PI / 180.0;
  for (int k = 0; k < 7; ++k) {
    const double a = M_PI + k * M_PI / 6.0;
    const Vector3d dir(std::cos(a) * std::cos(tilt), std::sin(a) * std::cos(tilt), std::sin(tilt));
    const Vector3d base = Vector3d(1.7 * std::cos(a), 1.7 * std::sin(a), 51.3);
    b.addCone(base, base + 3.4 * dir, 0.22, 12);
  }
  // Raised right arm with the torch; the flame tip is the top of the scene.
  const Vector3d hand(3.3, 0.1, 54.6);
  addLimb(b, Vector3d(2.7, 0, 45.9), Vector3d(3.5, 0.3, 50.6), hand, 1.0);
  const Vector3d axis(hand.x(), hand.y(), 0.0);
  b.addCylinder(axis + Vector3d(0, 0, 54.2), axis + Vector3d(0, 0, 57.0), 0.32, 24);
  b.addFrustum(axis + Vector3d(0, 0, 57.0), axis + Vector3d(0, 0, 58.3), 0.35, 1.0, 24);
  b.addCylinder(axis + Vector3d(0, 0, 57.55), axis + Vector3d(0, 0, 57.75), 1.35, kSegments);
  b.addCone(axis + Vector3d(0, 0, 58.3), axis + Vector3d(0, 0, 60.0), 0.75, 24);
  // Left arm holding a tablet against the body.
  addLimb(b, Vector3d(-2.7, 0, 45.9), Vector3d(-3.4, 0.2, 42.2), Vector3d(-3.5, -1.3, 41.0), 0.9);
  const double yaw = 199.0 * M_PI / 180.0;
  const Eigen::Matrix3d tablet = (Eigen::AngleAxisd(yaw, Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(-0.2, Vector3d::UnitY()))
                                     .matrix();
  b.addOrientedBox(Vector3d(3.3 * std::cos(yaw), 3.3 * std::sin(yaw), 40.0),
                   Vector3d(0.2, 1.1, 1.9), tablet);
}

void buildStatue(MeshBuilder& b) {
  addPedestal(b);
  addFigure(b);
}


// ---- multistorey: x in [-30, 30], y in [-20, 20], z in [0, 45.6] ----
//
// An open-sided parking structure in three terraced tiers: decks every
// kDeckPitch (0.3 m slabs, 3 m clear between them), the lower five 60 x 40 m,
// the next four 44 x 30 m, the top four 28 x 20 m. Each deck is joined to the
// one below by a 5 m wide ramp through a hole in it, stands on 0.5 m columns,
// and has 0.9 m parapets broken by 3 m gaps a UAV can enter by. Two closed
// 4 x 6 m stair cores rise through every deck to 45.6 m.

constexpr double kDeckPitch = 3.3;
constexpr double kSlab = 0.3;
constexpr int kDecks = 13;

struct Rect {
  double x0, x1, y0, y1;
  bool overlaps(const Rect& o, double margin) const {
    return x0 - margin < o.x1 && o.x0 < x1 + margin && y0 - margin < o.y1 && o.y0 < y1 + margin;
  }
};

Rect deckFootprint(int level) {
  if (level <= 5) return {-30, 30, -20, 20};
  if (level <= 9) return {-22, 22, -15, 15};
  return {-14, 14, -10, 10};
}

// The ramp up to `level` from the one below (and the hole it rises through):
// 16 m along x near the footprint's +y edge, climbing +x on odd levels.
Rect rampHole(int level) {
  const Rect f = deckFootprint(level);
  return {-8, 8, f.y1 - 7.5, f.y1 - 2.0};
}

const std::array<Rect, 2>& stairCores() {
  static const std::array<Rect, 2> cores = {Rect{-12, -8, -9, -3}, Rect{8, 12, -9, -3}};
  return cores;
}

// The rectangle `r` less `hole` (inside it), as up to four boxes.
void slabWithHole(MeshBuilder& b, const Rect& r, const Rect& hole, double z0, double z1) {
  auto box = [&](double x0, double x1, double y0, double y1) {
    if (x1 - x0 > 1e-6 && y1 - y0 > 1e-6) slab(b, x0, x1, y0, y1, z0, z1);
  };
  box(r.x0, r.x1, r.y0, hole.y0);
  box(r.x0, r.x1, hole.y1, r.y1);
  box(r.x0, hole.x0, hole.y0, hole.y1);
  box(hole.x1, r.x1, hole.y0, hole.y1);
}

// Parapet segments along one edge from a to b (one axis varies), 0.9 m high,
// with a 3 m gap in the middle of every 10 m bay.
void addParapetEdge(MeshBuilder& b, const Vector2d& a, const Vector2d& c, const Vector2d& inward, double z) {
  const double length = (c - a).norm();
  const Vector2d d = (c - a) / length;
  const int bays = std::max(1, static_cast<int>(std::round(length / 10.0)));
  const double bay = length / bays;
  for (int i = 0; i < bays; ++i) {
    for (const auto& [s0, s1] : {std::pair<double, double>{0.0, 0.5 * (bay - 3.0)},
                                 std::pair<double, double>{0.5 * (bay + 3.0), bay}}) {
      const Vector2d p0 = a + (i * bay + s0) * d, p1 = a + (i * bay + s1) * d;
      const Vector2d q0 = p0 + 0.2 * inward, q1 = p1 + 0.2 * inward;
      slab(b, std::min({p0.x(), p1.x(), q0.x(), q1.x()}), std::max({p0.x(), p1.x(), q0.x(), q1.x()}),
           std::min({p0.y(), p1.y(), q0.y(), q1.y()}), std::max({p0.y(), p1.y(), q0.y(), q1.y()}), z, z + 0.9);
    }
  }
}

void addParapets(MeshBuilder& b, const Rect& f, double z) {
  addParapetEdge(b, {f.x0, f.y0}, {f.x1, f.y0}, {0, 1}, z);
  addParapetEdge(b, {f.x0, f.y1}, {f.x1, f.y1}, {0, -1}, z);
  addParapetEdge(b, {f.x0, f.y0 + 0.2}, {f.x0, f.y1 - 0.2}, {1, 0}, z);
  addParapetEdge(b, {f.x1, f.y0 + 0.2}, {f.x1, f.y1 - 0.2}, {-1, 0}, z);
}

void buildMultistorey(MeshBuilder& b) {
  const double top = kDecks * kDeckPitch;
  for (int level = 1; level <= kDecks; ++level) {
    const Rect f = deckFootprint(level);
    const Rect hole = rampHole(level);
    const double z = level * kDeckPitch;
    slabWithHole(b, f, hole, z - kSlab, z);
    addParapets(b, f, z);
    // The ramp from the deck below, 0.3 m thick, its top flush with both decks.
    const double zl = z - kDeckPitch, yc = 0.5 * (hole.y0 + hole.y1);
    const double xs = level % 2 == 1 ? hole.x0 : hole.x1, xe = level % 2 == 1 ? hole.x1 : hole.x0;
    b.addBeam(Vector3d(xs, yc, std::max(zl - 0.5 * kSlab, 0.5 * kSlab)), Vector3d(xe, yc, z - 0.5 * kSlab), hole.y1 - hole.y0 - 0.4, kSlab);
    // Columns under the deck on a 9 x 8.5 m grid, clear of holes and cores.
    const Rect below_hole = level > 1 ? rampHole(level - 1) : Rect{0, 0, 0, 0};
    for (double x = -27; x <= 27.01; x += 9.0) {
      for (double y = -17; y <= 17.01; y += 8.5) {
        const Rect c{x - 0.25, x + 0.25, y - 0.25, y + 0.25};
        if (c.x0 < f.x0 + 0.5 || c.x1 > f.x1 - 0.5 || c.y0 < f.y0 + 0.5 || c.y1 > f.y1 - 0.5) continue;
        if (c.overlaps(hole, 0.3) || (level > 1 && c.overlaps(below_hole, 0.3))) continue;
        if (c.overlaps(stairCores()[0], 0.3) || c.overlaps(stairCores()[1], 0.3)) continue;
        slab(b, c.x0, c.x1, c.y0, c.y1, zl, z - kSlab);
      }
    }
  }
  for (const Rect& c : stairCores()) slab(b, c.x0, c.x1, c.y0, c.y1, 0, top + 2.7);
}

struct SceneEntry {
  const char* name;
  void (*build)(MeshBuilder&);
};

const std::vector<SceneEntry>& sceneTable() {
  static const std::vector<SceneEntry> table = {{"box", buildBox},
                                                {"sphere", buildSphere},
                                                {"room", buildRoom},
                                                {"plant", buildPlant},
                                                {"statue", buildStatue},
                                                {"multistorey", buildMultistorey}};
  return table;
}

}  // namespace

const std::vector<std::string>& proceduralSceneNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const SceneEntry& e : sceneTable()) out.emplace_back(e.name);
    return out;
  }();
  return names;
}

bool isProceduralScene(const std::string& name) {
  const std::vector<std::string>& names = proceduralSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Status makeProceduralScene(const std::string& name, TriangleMesh* mesh) {
  if (mesh == nullptr) return Status::Error("makeProceduralScene: null output mesh");
  for (const SceneEntry& e : sceneTable()) {
    if (name != e.name) continue;
    MeshBuilder builder;
    e.build(builder);
    *mesh = builder.take();
    mesh->removeDegenerate();
    return Status::Ok();
  }
  std::string known;
  for (const std::string& n : proceduralSceneNames()) known += (known.empty() ? "" : ", ") + n;
  return Status::Error("unknown procedural scene '" + name + "'; known scenes: " + known);
}

}  // namespace surface_nbv
