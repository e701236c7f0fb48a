#include "assets/polygon_mesh.h"

#include <geos_c.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

namespace inet {
namespace {

/// One GEOS context per call site and thread (the _r API keeps no global state).
class Geos {
 public:
  Geos() : ctx_(GEOS_init_r()) {}
  ~Geos() { GEOS_finish_r(ctx_); }
  Geos(const Geos&) = delete;
  Geos& operator=(const Geos&) = delete;
  GEOSContextHandle_t ctx() const { return ctx_; }

  using Ptr = std::unique_ptr<GEOSGeometry, std::function<void(GEOSGeometry*)>>;
  Ptr own(GEOSGeometry* g) const {
    GEOSContextHandle_t c = ctx_;
    return Ptr(g, [c](GEOSGeometry* x) {
      if (x) GEOSGeom_destroy_r(c, x);
    });
  }

  /// A valid polygon (or multipolygon) of the ring; nullptr for fewer than 3 distinct points.
  Ptr polygon(const Ring& r) const {
    if (r.size() < 3) return own(nullptr);
    GEOSCoordSequence* seq = GEOSCoordSeq_create_r(ctx_, unsigned(r.size() + 1), 2);
    for (size_t i = 0; i <= r.size(); ++i) {
      const auto& p = r[i % r.size()];
      GEOSCoordSeq_setXY_r(ctx_, seq, unsigned(i), p.x(), p.y());
    }
    GEOSGeometry* ring = GEOSGeom_createLinearRing_r(ctx_, seq);
    if (!ring) return own(nullptr);
    Ptr poly = own(GEOSGeom_createPolygon_r(ctx_, ring, nullptr, 0));
    if (poly && GEOSisValid_r(ctx_, poly.get()) != 1) {
      Ptr fixed = own(GEOSMakeValid_r(ctx_, poly.get()));
      return fixed;
    }
    return poly;
  }

  Ring ringOf(const GEOSGeometry* ring) const {
    Ring out;
    const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(ctx_, ring);
    unsigned n = 0;
    GEOSCoordSeq_getSize_r(ctx_, seq, &n);
    for (unsigned i = 0; i + 1 < n; ++i) {  // the last point repeats the first
      double x = 0, y = 0;
      GEOSCoordSeq_getXY_r(ctx_, seq, i, &x, &y);
      out.emplace_back(x, y);
    }
    return out;
  }

  /// Every polygon in `g` (a polygon, multipolygon or collection), recursively.
  void polygons(const GEOSGeometry* g, std::vector<const GEOSGeometry*>& out) const {
    if (!g) return;
    const int type = GEOSGeomTypeId_r(ctx_, g);
    if (type == GEOS_POLYGON) {
      out.push_back(g);
    } else if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
      const int n = GEOSGetNumGeometries_r(ctx_, g);
      for (int i = 0; i < n; ++i) polygons(GEOSGetGeometryN_r(ctx_, g, i), out);
    }
  }

 private:
  GEOSContextHandle_t ctx_;
};

}  // namespace

double signedArea2(const Ring& r) {
  double a = 0;
  for (size_t i = 0; i < r.size(); ++i) {
    const auto& p = r[i];
    const auto& q = r[(i + 1) % r.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return a;
}

std::vector<Triangle2> triangulateDifference(const Ring& outer, const std::vector<Ring>& holes) {
  const Geos g;
  Geos::Ptr shape = g.polygon(outer);
  if (!shape) return {};
  for (const Ring& h : holes) {
    Geos::Ptr hole = g.polygon(h);
    if (!hole) continue;
    Geos::Ptr rest = g.own(GEOSDifference_r(g.ctx(), shape.get(), hole.get()));
    if (!rest) continue;  // GEOS could not cut it: keep the face whole rather than lose it
    shape = std::move(rest);
  }
  std::vector<Triangle2> out;
  Geos::Ptr tris = g.own(GEOSConstrainedDelaunayTriangulation_r(g.ctx(), shape.get()));
  std::vector<const GEOSGeometry*> polys;
  g.polygons(tris.get(), polys);
  for (const GEOSGeometry* p : polys) {
    const Ring r = g.ringOf(GEOSGetExteriorRing_r(g.ctx(), p));
    if (r.size() != 3) continue;
    Triangle2 t{r[0], r[1], r[2]};
    const double a = signedArea2(r);
    if (std::abs(a) < 1e-14) continue;
    if (a < 0) std::swap(t[1], t[2]);
    out.push_back(t);
  }
  return out;
}

std::vector<Triangle2> triangulatePolygon(const Ring& outer) {
  return triangulateDifference(outer, {});
}

std::vector<Ring> intersectionRings(const Ring& a, const Ring& b) {
  const Geos g;
  Geos::Ptr pa = g.polygon(a), pb = g.polygon(b);
  if (!pa || !pb) return {};
  Geos::Ptr both = g.own(GEOSIntersection_r(g.ctx(), pa.get(), pb.get()));
  std::vector<const GEOSGeometry*> polys;
  g.polygons(both.get(), polys);
  std::vector<Ring> out;
  for (const GEOSGeometry* p : polys) {
    out.push_back(g.ringOf(GEOSGetExteriorRing_r(g.ctx(), p)));
    const int n = GEOSGetNumInteriorRings_r(g.ctx(), p);
    for (int i = 0; i < n; ++i) out.push_back(g.ringOf(GEOSGetInteriorRingN_r(g.ctx(), p, i)));
  }
  return out;
}

FaceWithHoles faceWithHoles(const Ring& outline, const std::vector<Ring>& holes, bool reveals,
                            double floor_v) {
  FaceWithHoles out;
  out.triangles = triangulateDifference(outline, holes);
  if (!reveals) return out;
  for (const Ring& h : holes) {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& p : h) centre += p;
    centre /= double(h.size());
    for (const Ring& r : intersectionRings(h, outline))
      for (size_t i = 0; i < r.size(); ++i) {
        const Eigen::Vector2d p = r[i], q = r[(i + 1) % r.size()];
        if (std::abs(p.y() - floor_v) < 1e-6 && std::abs(q.y() - floor_v) < 1e-6) continue;
        out.reveals.push_back({p, q, centre - (p + q) / 2});
      }
  }
  return out;
}

std::vector<Ring> enclosedFaces(const std::vector<std::array<Eigen::Vector2d, 2>>& segments,
                                double min_area) {
  const Geos g;
  std::vector<GEOSGeometry*> lines;
  for (const auto& s : segments) {
    if ((s[0] - s[1]).norm() < 1e-9) continue;
    GEOSCoordSequence* seq = GEOSCoordSeq_create_r(g.ctx(), 2, 2);
    GEOSCoordSeq_setXY_r(g.ctx(), seq, 0, s[0].x(), s[0].y());
    GEOSCoordSeq_setXY_r(g.ctx(), seq, 1, s[1].x(), s[1].y());
    if (GEOSGeometry* l = GEOSGeom_createLineString_r(g.ctx(), seq)) lines.push_back(l);
  }
  if (lines.empty()) return {};
  // the collection takes the lines; the union nodes them where they cross or touch
  Geos::Ptr all = g.own(GEOSGeom_createCollection_r(g.ctx(), GEOS_MULTILINESTRING, lines.data(),
                                                    unsigned(lines.size())));
  Geos::Ptr noded = g.own(GEOSUnaryUnion_r(g.ctx(), all.get()));
  if (!noded) return {};
  const GEOSGeometry* in[] = {noded.get()};
  Geos::Ptr faces = g.own(GEOSPolygonize_r(g.ctx(), in, 1));
  std::vector<const GEOSGeometry*> polys;
  g.polygons(faces.get(), polys);
  std::vector<Ring> out;
  for (const GEOSGeometry* p : polys) {
    Ring r = g.ringOf(GEOSGetExteriorRing_r(g.ctx(), p));
    const double a = signedArea2(r) / 2;
    if (std::abs(a) < min_area) continue;
    if (a < 0) std::reverse(r.begin(), r.end());
    out.push_back(std::move(r));
  }
  return out;
}

double intersectionArea(const Ring& a, const Ring& b) {
  const Geos g;
  Geos::Ptr pa = g.polygon(a), pb = g.polygon(b);
  if (!pa || !pb) return 0.0;
  Geos::Ptr both = g.own(GEOSIntersection_r(g.ctx(), pa.get(), pb.get()));
  double area = 0;
  if (both) GEOSArea_r(g.ctx(), both.get(), &area);
  return area;
}

}  // namespace inet
