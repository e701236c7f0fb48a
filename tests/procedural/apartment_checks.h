#pragma once
// The layout acceptance rules of procedural/apartment.h, checked on a built apartment (shared by
// the parametric and the catalog-furnished tests).
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "procedural/apartment.h"

namespace inet::test {

/// Deepest overlap of two boxes (the smallest extent of their intersection), 0 when apart.
inline double penetration(const Eigen::AlignedBox3d& a, const Eigen::AlignedBox3d& b) {
  const Eigen::AlignedBox3d i = a.intersection(b);
  return i.isEmpty() ? 0.0 : i.sizes().minCoeff();
}

inline void checkApartment(const Apartment& apt) {
  // every room reachable from the front door through free floor (0.1 m grid, 0.25 m radius)
  std::vector<double> free;
  const std::vector<bool> reached = reachableRooms(apt, 0.1, 0.25, &free);
  for (size_t r = 0; r < reached.size(); ++r) {
    EXPECT_TRUE(reached[r]) << "room " << apt.scene.rooms[r].id << " unreachable";
    EXPECT_GE(free[r], 0.6) << "room " << apt.scene.rooms[r].id << " free floor";
  }
  // furniture: inside its room, no interpenetration (walls and floors are the shell)
  const double t = apt.plan.wall_thickness / 2;
  std::vector<const PlacedPiece*> furniture;
  for (const PlacedPiece& p : apt.pieces) {
    static const std::set<std::string> shell = {"wall",     "floor", "ceiling", "ground",
                                                "skirting", "door",  "window"};
    if (shell.count(p.category)) continue;
    furniture.push_back(&p);
    ASSERT_GE(p.room, 0) << p.name;
    const auto& b = apt.plan.rooms[p.room].box;
    for (const auto& h : p.hulls) {
      EXPECT_GE(h.min().x(), b.min().x() + t - 0.01) << p.name;
      EXPECT_GE(h.min().y(), b.min().y() + t - 0.01) << p.name;
      EXPECT_LE(h.max().x(), b.max().x() - t + 0.01) << p.name;
      EXPECT_LE(h.max().y(), b.max().y() - t + 0.01) << p.name;
      EXPECT_GE(h.min().z(), -0.01) << p.name;
      EXPECT_LE(h.max().z(), apt.plan.ceiling + 0.01) << p.name;
    }
  }
  // every piece is held up: by the floor (its bottom at 0), by a support piece (its bottom at
  // one of the support's surface heights, its footprint on the support's top), or hung on a
  // wall or the ceiling
  for (const PlacedPiece* p : furniture) {
    Eigen::AlignedBox3d all;
    for (const auto& h : p->hulls) all.extend(h);
    if (p->rests_on == "floor") {
      EXPECT_NEAR(all.min().z(), 0.0, 0.01) << p->name << " floats or sinks";
    } else if (p->rests_on == "support") {
      ASSERT_GE(p->support, 0) << p->name;
      const PlacedPiece& s = apt.pieces[p->support];
      EXPECT_NEAR(all.min().z(), p->support_z, 0.01) << p->name << " on " << s.name;
      Eigen::AlignedBox3d top;
      for (const auto& h : s.hulls) top.extend(h);
      EXPECT_LE(p->support_z, top.max().z() + 0.01) << p->name;
      EXPECT_GE(all.min().x(), top.min().x() - 0.01) << p->name << " overhangs " << s.name;
      EXPECT_LE(all.max().x(), top.max().x() + 0.01) << p->name << " overhangs " << s.name;
      EXPECT_GE(all.min().y(), top.min().y() - 0.01) << p->name << " overhangs " << s.name;
      EXPECT_LE(all.max().y(), top.max().y() + 0.01) << p->name << " overhangs " << s.name;
    } else {
      EXPECT_TRUE(p->rests_on == "wall" || p->rests_on == "ceiling") << p->name;
      if (p->rests_on == "ceiling") {
        EXPECT_NEAR(all.max().z(), apt.plan.ceiling, 0.01) << p->name;
      }
    }
  }
  for (size_t i = 0; i < furniture.size(); ++i)
    for (size_t j = i + 1; j < furniture.size(); ++j) {
      if (furniture[i]->flat || furniture[j]->flat) continue;  // rugs lie under things
      for (const auto& a : furniture[i]->hulls)
        for (const auto& b : furniture[j]->hulls)
          EXPECT_LE(penetration(a, b), 0.01)
              << furniture[i]->name << " and " << furniture[j]->name << " interpenetrate";
    }
}

}  // namespace inet::test
