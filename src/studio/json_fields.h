#pragma once
// Reading a request's JSON fields with the command line's rules: every key checked against the
// ones the route takes, every value's type checked, and each problem an InputError("", key,
// problem) naming the key as the page sends it (the server answers 400 with that line).
#include <nlohmann/json.hpp>

#include <cstdint>
#include <set>
#include <string>

#include "core/pose.h"
#include "trajectory/trajectory.h"

namespace inet::studio {

/// Throws unless `body` is a JSON object whose keys are all in `keys` (the message lists them).
void checkKeys(const nlohmann::json& body, const std::set<std::string>& keys,
               const std::string& where = "request body");
/// body[key] as a number, `fallback` when absent.
double number(const nlohmann::json& body, const std::string& key, double fallback);
/// body[key] as an integer (no fraction), `fallback` when absent.
int64_t integer(const nlohmann::json& body, const std::string& key, int64_t fallback);
/// body[key] as an integer in lo..hi, `fallback` when absent.
int integerIn(const nlohmann::json& body, const std::string& key, int fallback, int lo, int hi);
/// body[key] as a string, `fallback` when absent.
std::string text(const nlohmann::json& body, const std::string& key, const std::string& fallback);
/// body[key] as three finite numbers [x, y, z]; required.
Vec3 vec3(const nlohmann::json& body, const std::string& key);
/// "--v-mult" -> "v_mult": the command line's flags as the request's keys, in a field name or
/// inside a message ("need 0 <= --min-height < --max-height").
std::string flagToKey(const std::string& text);
/// [{"t_ns", "position": [x, y, z], "quaternion_xyzw": [x, y, z, w]}, ...] with t_ns counted
/// from the first pose and quaternions with w >= 0.
nlohmann::json posesJson(const Trajectory& traj);

}  // namespace inet::studio
