#include "config_parts.hpp"

#include <algorithm>
#include <climits>
#include <cmath>

namespace xshell {

namespace {

nlohmann::json vector3_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// A non-empty list of distinct integers, each in [lo, hi]; `what` names one
// in messages ("vertex", "rod").
std::vector<int> distinct_integers(const JsonField& f, const std::string& what, int lo, int hi) {
  std::vector<int> out;
  for (const JsonField& item : f.elements()) {
    const int n = item.integer();
    if (n < lo || n > hi)
      item.fail("a " + what + " must be in [" + std::to_string(lo) + ", " +
                (hi == INT_MAX ? std::string("...") : std::to_string(hi)) + "], got " +
                std::to_string(n));
    if (std::find(out.begin(), out.end(), n) != out.end())
      item.fail(what + " " + std::to_string(n) + " is listed twice");
    out.push_back(n);
  }
  if (out.empty()) f.fail("must list at least one " + what);
  return out;
}

const char* const kAxes[] = {"x", "y", "z"};

void read_region(const JsonField& f, SupportSelect& s) {
  f.check_keys({"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"});
  bool any = false;
  for (int c = 0; c < 3; ++c) {
    const std::string axis = kAxes[c];
    if (auto lo = f.find(axis + "_min")) {
      s.region_min[c] = lo->number();
      any = true;
    }
    if (auto hi = f.find(axis + "_max")) {
      s.region_max[c] = hi->number();
      any = true;
    }
    if (s.region_min[c] > s.region_max[c])
      f.fail(axis + "_min is above " + axis + "_max: the region is empty");
  }
  if (!any) f.fail("needs at least one of x_min, x_max, y_min, y_max, z_min, z_max");
}

}  // namespace

GraphTransform read_transform(const JsonField& f) {
  f.check_keys({"mirror", "scale", "rotate_deg", "translate"});
  GraphTransform t;
  if (auto mirror = f.find("mirror")) {
    const std::string axis = mirror->string();
    const auto at = std::find(std::begin(kAxes), std::end(kAxes), axis);
    if (at == std::end(kAxes)) mirror->fail("expected \"x\", \"y\" or \"z\", got \"" + axis + "\"");
    t.mirror = static_cast<int>(at - std::begin(kAxes));
  }
  if (auto scale = f.find("scale")) {
    t.scale = scale->number();
    if (!(t.scale > 0)) scale->fail("must be > 0, got " + scale->value().dump());
  }
  if (auto rotate = f.find("rotate_deg")) t.rotate_deg = rotate->vector3();
  if (auto translate = f.find("translate")) t.translate = translate->vector3();
  return t;
}

nlohmann::json transform_json(const GraphTransform& t) {
  return {{"mirror", t.mirror < 0 ? nlohmann::json(nullptr) : nlohmann::json(kAxes[t.mirror])},
          {"scale", t.scale},
          {"rotate_deg", vector3_json(t.rotate_deg)},
          {"translate", vector3_json(t.translate)}};
}

SupportSelect read_select(const JsonField& f) {
  SupportSelect s;
  if (f.is_string()) {
    if (f.string() != "boundary")
      f.fail(
          "expected \"boundary\", {\"valence\": [...]}, {\"region\": {...}} or a list of "
          "vertices, got \"" +
          f.string() + "\"");
    s.kind = SelectKind::Boundary;
  } else if (f.value().is_array()) {
    s.kind = SelectKind::Vertices;
    s.vertices = distinct_integers(f, "vertex", 0, INT_MAX);
  } else {
    f.check_keys({"valence", "region"});
    const auto valence = f.find("valence");
    const auto region = f.find("region");
    if (valence.has_value() == region.has_value())
      f.fail("needs exactly one of \"valence\" and \"region\"");
    if (valence) {
      s.kind = SelectKind::Valence;
      s.valences = distinct_integers(*valence, "valence", 1, 4);
    } else {
      s.kind = SelectKind::Region;
      read_region(*region, s);
    }
  }
  return s;
}

nlohmann::json select_json(const SupportSelect& s) {
  switch (s.kind) {
    case SelectKind::Boundary:
      return "boundary";
    case SelectKind::Valence:
      return {{"valence", s.valences}};
    case SelectKind::Region: {
      nlohmann::json region = nlohmann::json::object();
      for (int c = 0; c < 3; ++c) {
        if (std::isfinite(s.region_min[c]))
          region[std::string(kAxes[c]) + "_min"] = s.region_min[c];
        if (std::isfinite(s.region_max[c]))
          region[std::string(kAxes[c]) + "_max"] = s.region_max[c];
      }
      return {{"region", region}};
    }
    case SelectKind::Vertices:
      break;
  }
  return s.vertices;
}

LineLoadConfig read_line_load(const JsonField& f) {
  f.check_keys({"rods", "force_per_length"});
  LineLoadConfig l;
  const JsonField rods = f.require("rods");
  if (rods.is_string()) {
    if (rods.string() != "all")
      rods.fail("expected \"all\" or a list of rod indices, got \"" + rods.string() + "\"");
  } else {
    l.rods = distinct_integers(rods, "rod", 0, INT_MAX);
  }
  l.force_per_length = f.require("force_per_length").vector3();
  return l;
}

nlohmann::json line_load_json(const LineLoadConfig& l) {
  return {{"rods", l.rods.empty() ? nlohmann::json("all") : nlohmann::json(l.rods)},
          {"force_per_length", vector3_json(l.force_per_length)}};
}

}  // namespace xshell
