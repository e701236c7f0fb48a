#include "scene/default_scene.h"

#include <cmath>

#include "core/error.h"
#include "scene/nyu40.h"
#include "scene/primitives.h"

namespace inet {
namespace {

class Builder {
 public:
  Builder() {
    scene_.name = "default_room";
    for (const char* p : {"box", "cylinder", "quad"}) {
      Mesh m = makePrimitive(p, {}, "built-in", "default scene");
      m.id = p;
      scene_.meshes.push_back(std::move(m));
    }
    Mesh ball = makePrimitive("sphere", {{"radius", 1.0}}, "built-in", "default scene");
    ball.id = "sphere";
    scene_.meshes.push_back(std::move(ball));
  }

  void material(const char* id, Vec3f albedo, Vec3f emission = Vec3f::Zero()) {
    Material m;
    m.id = id;
    m.albedo = albedo;
    m.emission = emission;
    scene_.materials.push_back(m);
  }

  /// Starts a new instance (one piece of furniture) with an NYU40 class name.
  void instance(const char* name, const char* category) {
    auto id = nyu40FromName(category);
    INET_CHECK_MSG(id.has_value(), category);
    current_name_ = name;
    current_label_ = *id;
    ++current_instance_;
    part_ = 0;
  }

  /// Adds a part of the current instance: `mesh` scaled by `size`, rotated (about z by yaw, then
  /// about x by tilt_x) and centred at `centre`.
  void part(const char* mesh, const char* material, Vec3 centre, Vec3 size, double yaw = 0,
            double tilt_x = 0) {
    Object o;
    o.name = current_name_;
    if (part_ > 0) o.name.append("_").append(std::to_string(part_));
    ++part_;
    o.mesh = scene_.findMesh(mesh);
    o.material = scene_.findMaterial(material);
    INET_CHECK(o.mesh >= 0 && o.material >= 0);
    Eigen::Affine3d a = Eigen::Translation3d(centre) * Eigen::AngleAxisd(yaw, Vec3::UnitZ()) *
                        Eigen::AngleAxisd(tilt_x, Vec3::UnitX()) * Eigen::Scaling(size);
    o.T_world_object = a.matrix();
    o.nyu40 = current_label_;
    o.instance = current_instance_;
    scene_.objects.push_back(o);
  }

  Scene take() { return std::move(scene_); }

 private:
  Scene scene_;
  std::string current_name_;
  int current_label_ = 0;
  int current_instance_ = 0;
  int part_ = 0;
};

void materials(Builder& b) {
  b.material("wall_paint", {0.72f, 0.70f, 0.65f});
  b.material("ceiling_white", {0.80f, 0.80f, 0.80f});
  b.material("floor_wood", {0.42f, 0.28f, 0.16f});
  b.material("wood_dark", {0.22f, 0.13f, 0.07f});
  b.material("wood_light", {0.60f, 0.45f, 0.30f});
  b.material("fabric_blue", {0.12f, 0.22f, 0.45f});
  b.material("fabric_red", {0.55f, 0.12f, 0.10f});
  b.material("linen", {0.85f, 0.83f, 0.78f});
  b.material("metal", {0.50f, 0.50f, 0.52f});
  b.material("rug", {0.45f, 0.32f, 0.50f});
  b.material("canvas", {0.20f, 0.50f, 0.35f});
  b.material("screen_black", {0.03f, 0.03f, 0.03f});
  b.material("book_a", {0.60f, 0.20f, 0.15f});
  b.material("book_b", {0.15f, 0.35f, 0.55f});
  b.material("book_c", {0.75f, 0.65f, 0.30f});
  b.material("ceramic", {0.80f, 0.78f, 0.70f});
  // emitters: radiance in W sr^-1 m^-2 (linear RGB), one-sided along the geometric normal
  b.material("ceiling_panel", {0.8f, 0.8f, 0.8f}, {12.0f, 11.5f, 10.5f});
  b.material("daylight", {0.0f, 0.0f, 0.0f}, {2.2f, 2.5f, 3.0f});
  b.material("lamp_shade", {0.9f, 0.85f, 0.7f}, {4.0f, 3.2f, 2.0f});
}

void shell(Builder& b) {
  b.instance("floor", "floor");
  b.part("box", "floor_wood", {2.5, 2.0, -0.05}, {5.2, 4.2, 0.1});
  b.instance("ceiling", "ceiling");
  b.part("box", "ceiling_white", {2.5, 2.0, 2.75}, {5.2, 4.2, 0.1});
  b.instance("wall_west", "wall");
  b.part("box", "wall_paint", {-0.05, 2.0, 1.35}, {0.1, 4.2, 2.7});
  b.instance("wall_east", "wall");
  b.part("box", "wall_paint", {5.05, 2.0, 1.35}, {0.1, 4.2, 2.7});
  b.instance("wall_south", "wall");
  b.part("box", "wall_paint", {2.5, -0.05, 1.35}, {5.2, 0.1, 2.7});
  b.instance("wall_north", "wall");
  b.part("box", "wall_paint", {2.5, 4.05, 1.35}, {5.2, 0.1, 2.7});
  b.instance("ceiling_light", "lamp");  // quad normal +z turned to face down
  b.part("quad", "ceiling_panel", {2.5, 2.0, 2.695}, {1.0, 0.6, 1.0}, 0, M_PI);
  b.instance("window", "window");  // quad turned to face -y, into the room
  b.part("quad", "daylight", {2.9, 3.995, 1.65}, {1.4, 1.0, 1.0}, 0, M_PI / 2);
  b.part("box", "wood_light", {2.9, 3.92, 1.13}, {1.5, 0.16, 0.04});
  b.instance("door", "door");
  b.part("box", "wood_light", {4.05, 0.02, 1.0}, {0.9, 0.04, 2.0});
  b.part("sphere", "metal", {3.7, 0.07, 1.0}, {0.035, 0.035, 0.035});
  b.instance("rug", "floor_mat");
  b.part("box", "rug", {2.6, 2.2, 0.005}, {2.0, 1.4, 0.01});
}

void tableWithLegs(Builder& b, const char* mat, Vec3 c, Vec3 top, double leg_r) {
  double h = c.z();
  b.part("box", mat, {c.x(), c.y(), h - top.z() / 2}, top);
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      b.part("cylinder", mat,
             {c.x() + sx * (top.x() / 2 - 2 * leg_r), c.y() + sy * (top.y() / 2 - 2 * leg_r),
              (h - top.z()) / 2},
             {2 * leg_r, 2 * leg_r, h - top.z()});
}

void furniture(Builder& b) {
  b.instance("bed", "bed");
  b.part("box", "wood_dark", {4.0, 2.0, 0.2}, {2.0, 1.6, 0.4});
  b.part("box", "linen", {3.98, 2.0, 0.5}, {1.9, 1.5, 0.2});
  b.part("box", "wood_dark", {4.93, 2.0, 0.7}, {0.1, 1.6, 1.0});
  b.instance("pillow_left", "pillow");
  b.part("box", "fabric_red", {4.6, 1.6, 0.67}, {0.35, 0.55, 0.14});
  b.instance("pillow_right", "pillow");
  b.part("box", "linen", {4.6, 2.4, 0.67}, {0.35, 0.55, 0.14});
  b.instance("night_stand", "night stand");
  b.part("box", "wood_light", {4.7, 3.2, 0.275}, {0.5, 0.5, 0.55});
  b.instance("bedside_lamp", "lamp");
  b.part("cylinder", "metal", {4.7, 3.2, 0.6}, {0.16, 0.16, 0.1});
  b.part("cylinder", "metal", {4.7, 3.2, 0.8}, {0.03, 0.03, 0.3});
  b.part("cylinder", "lamp_shade", {4.7, 3.2, 1.05}, {0.3, 0.3, 0.25});
  b.instance("wardrobe", "cabinet");
  b.part("box", "wood_light", {0.8, 3.7, 1.0}, {1.2, 0.6, 2.0});
  b.instance("bookshelf", "bookshelf");
  b.part("box", "wood_dark", {0.02, 2.0, 0.9}, {0.04, 1.0, 1.8});
  for (double y : {1.515, 2.485}) b.part("box", "wood_dark", {0.2, y, 0.9}, {0.4, 0.03, 1.8});
  for (double z : {0.015, 0.45, 0.9, 1.35, 1.785})
    b.part("box", "wood_dark", {0.2, 2.0, z}, {0.4, 0.94, 0.03});
  b.instance("books", "books");
  const char* book_mats[] = {"book_a", "book_b", "book_c"};
  for (int shelf = 0; shelf < 3; ++shelf) {
    double z0 = 0.465 + shelf * 0.45, y = 1.56;
    for (int k = 0; y < 2.3 + 0.1 * shelf; ++k) {
      double w = 0.04 + 0.015 * ((k * 7 + shelf) % 3), h = 0.22 + 0.04 * ((k * 5 + shelf) % 4);
      b.part("box", book_mats[(k + shelf) % 3], {0.2, y + w / 2, z0 + h / 2}, {0.28, w, h});
      y += w + 0.005;
    }
  }
  b.instance("desk", "desk");
  tableWithLegs(b, "wood_light", {1.6, 0.4, 0.75}, {1.2, 0.6, 0.04}, 0.025);
  b.instance("desk_chair", "chair");
  b.part("box", "fabric_red", {1.6, 1.0, 0.45}, {0.45, 0.45, 0.05});
  b.part("box", "fabric_red", {1.6, 1.2, 0.72}, {0.45, 0.05, 0.5});
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      b.part("cylinder", "metal", {1.6 + sx * 0.19, 1.0 + sy * 0.19, 0.21}, {0.03, 0.03, 0.42});
  b.instance("picture_desk", "picture");
  b.part("box", "wood_dark", {1.6, 0.015, 1.6}, {0.85, 0.03, 0.6});
  b.part("box", "canvas", {1.6, 0.032, 1.6}, {0.75, 0.01, 0.5});
  b.instance("picture_bed", "picture");
  b.part("box", "canvas", {4.985, 2.0, 1.75}, {0.03, 1.0, 0.6});
}

void livingArea(Builder& b) {
  b.instance("sofa", "sofa");
  b.part("box", "fabric_blue", {2.9, 3.55, 0.22}, {1.8, 0.8, 0.44});
  b.part("box", "fabric_blue", {2.9, 3.87, 0.65}, {1.8, 0.16, 0.5});
  b.part("box", "fabric_blue", {2.07, 3.55, 0.55}, {0.14, 0.8, 0.26});
  b.part("box", "fabric_blue", {3.73, 3.55, 0.55}, {0.14, 0.8, 0.26});
  b.instance("coffee_table", "table");
  tableWithLegs(b, "wood_dark", {2.9, 2.75, 0.42}, {1.0, 0.5, 0.04}, 0.02);
  b.instance("ball", "otherprop");
  b.part("sphere", "fabric_red", {3.15, 2.75, 0.5}, {0.08, 0.08, 0.08});
  b.instance("vase", "otherprop");
  b.part("cylinder", "ceramic", {2.65, 2.75, 0.52}, {0.12, 0.12, 0.2});
  b.instance("tv_stand", "cabinet");
  b.part("box", "wood_dark", {0.25, 0.8, 0.25}, {0.5, 1.1, 0.5});
  b.instance("television", "television");
  b.part("box", "screen_black", {0.12, 0.8, 0.87}, {0.05, 1.0, 0.6});
  b.part("box", "metal", {0.2, 0.8, 0.53}, {0.15, 0.3, 0.06});
}

}  // namespace

Scene makeDefaultScene() {
  Builder b;
  materials(b);
  shell(b);
  furniture(b);
  livingArea(b);
  Scene s = b.take();
  s.validate("built-in default scene");
  return s;
}

}  // namespace inet
