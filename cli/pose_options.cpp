#include "pose_options.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "common.hpp"
#include "topple/bodies/pose.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"

namespace topple::cli {
namespace {

/// "a,b,c": exactly `count` numbers separated by commas (spaces allowed around them), or parameter_error(option).
std::vector<double> number_list(const std::string& text, std::size_t count, const std::string& option,
                                const char* what) {
  std::vector<double> out;
  std::size_t at = 0;
  while (true) {
    const std::size_t comma = text.find(',', at);
    std::string item = text.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    const auto first = item.find_first_not_of(" \t"), last = item.find_last_not_of(" \t");
    item = first == std::string::npos ? std::string() : item.substr(first, last - first + 1);
    double x = 0.0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), x);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size() || !std::isfinite(x)) {
      throw parameter_error(option, fmt::format("'{}' is not {} ({} finite numbers separated by commas)", text,
                                                what, count));
    }
    out.push_back(x);
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  if (out.size() != count) {
    throw parameter_error(option, fmt::format("'{}' holds {} numbers; {} takes {}: {}", text, out.size(), option,
                                              count, what));
  }
  return out;
}

}  // namespace

void add_pose_options(CLI::App& cmd, PoseOptionsText& text, BodyOptions& body, const std::string& with) {
  cmd.add_option("--pose", text.pose,
                 with + "rest: on the stable face of the convex hull nearest the scanned pose (or --up, --rotation, "
                        "--axis-angle, --face), levelled by the minimal rotation; as-scanned: on the mesh's lowest "
                        "plane as given (the earlier answer)")
      ->capture_default_str();
  cmd.add_option("--up", text.up,
                 with + "rest: the direction x,y,z of the mesh that becomes up; then the nearest stable face");
  cmd.add_option("--rotation", text.rotation,
                 with + "rest: turn the mesh first by this unit quaternion w,x,y,z (about its CM); then the nearest "
                        "stable face");
  cmd.add_option("--axis-angle", text.axis_angle,
                 with + "rest: turn the mesh first by this angle about this axis: x,y,z,degrees; then the nearest "
                        "stable face");
  cmd.add_option("--face", text.face, with + "rest: the face of this number in `topple body --list-faces` (must be "
                                             "stable)");
  cmd.add_option("--contact-tolerance", text.contact_tolerance,
                 with + "rest: hull facets within this length of a face's plane are one face, e.g. 2mm (default 1mm)");
  cmd.add_option("--base-tolerance", body.base_tolerance_fraction,
                 with + "as-scanned: vertices within this fraction of the mesh's size above its lowest point are in "
                        "contact (given without --pose, it means --pose as-scanned, as before the resting pose)")
      ->capture_default_str();
}

void apply_pose_options(const CLI::App& cmd, PoseOptionsText& text, BodyOptions& body) {
  // --base-tolerance is the as-scanned pose's contact (its meaning before the resting pose): a command line with it
  // and no --pose means what it meant, the as-scanned pose; with --pose rest it has nothing to set.
  const bool base_given = cmd.count("--base-tolerance") > 0, pose_given = cmd.count("--pose") > 0;
  if (base_given && !pose_given) text.pose = "as-scanned";
  if (base_given && text.pose == "rest") {
    throw parameter_error("--base-tolerance", "is the as-scanned pose's contact (a fraction of the mesh's size); "
                                              "the resting pose takes --contact-tolerance (a length)");
  }
  if (cmd.count("--contact-tolerance") > 0 && text.pose == "as-scanned") {
    throw parameter_error("--contact-tolerance", "is the resting pose's; the as-scanned pose takes --base-tolerance");
  }
  if (text.pose == "rest") {
    body.pose = PoseMethod::rest;
  } else if (text.pose == "as-scanned") {
    body.pose = PoseMethod::as_scanned;
  } else {
    throw parameter_error("--pose", fmt::format("'{}' is not a pose: rest or as-scanned", text.pose));
  }
  if (!text.up.empty()) {
    const auto v = number_list(text.up, 3, "--up", "a direction x,y,z in the mesh's coordinates");
    body.up = Vec3{v[0], v[1], v[2]};
  }
  if (!text.rotation.empty()) {
    const auto v = number_list(text.rotation, 4, "--rotation", "a unit quaternion w,x,y,z");
    body.rotation_wxyz = Quaternion{v[0], v[1], v[2], v[3]};
  }
  if (!text.axis_angle.empty()) {
    const auto v = number_list(text.axis_angle, 4, "--axis-angle", "an axis x,y,z and an angle in degrees");
    body.axis_angle_deg = std::array<double, 4>{v[0], v[1], v[2], v[3]};
  }
  if (!text.contact_tolerance.empty()) {
    body.contact_tolerance_m = parse_length_m(text.contact_tolerance, "--contact-tolerance");
  }
  body.face = text.face;
}

}  // namespace topple::cli
