#include "config.hpp"

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "config_parts.hpp"
#include "config_values.hpp"
#include "design_config.hpp"
#include "input_error.hpp"
#include "input_file.hpp"
#include "json_field.hpp"
#include "optional_json.hpp"

namespace xshell {
namespace {

// ---------------------------------------------------------------------------
// The spelling of every enum in the file

template <typename E>
using Names = std::vector<std::pair<E, std::string>>;

const Names<RestShape> kRestShapes = {{RestShape::Input, "input"},
                                      {RestShape::Straight, "straight"}};
const Names<JointModel> kJointModels = {{JointModel::Rotation, "rotation"},
                                        {JointModel::EdgeVectors, "edge_vectors"}};
const Names<SectionShape> kShapes = {{SectionShape::Rectangle, "rectangle"},
                                     {SectionShape::Ellipse, "ellipse"}};
const Names<SolverMethod> kMethods = {{SolverMethod::Newton, "newton"},
                                      {SolverMethod::Dynamics, "dynamics"},
                                      {SolverMethod::KineticDamping, "kinetic-damping"}};
const Names<LineSearchSetting> kLineSearches = {{LineSearchSetting::Energy, "energy"},
                                                {LineSearchSetting::Kinsol, "kinsol"}};
const Names<MassSetting> kMasses = {{MassSetting::Physical, "physical"},
                                    {MassSetting::Fictitious, "fictitious"}};
const Names<StartSetting> kStarts = {{StartSetting::SlowManifold, "slow_manifold"},
                                     {StartSetting::Rest, "rest"}};
const Names<OutputFormat> kFormats = {{OutputFormat::Binary, "binary"},
                                      {OutputFormat::Ascii, "ascii"}};
const Names<OutputCompression> kCompressions = {{OutputCompression::Lz4, "lz4"},
                                                {OutputCompression::Zlib, "zlib"},
                                                {OutputCompression::None, "none"}};
const Names<Fixed> kFixed = {{Fixed::Position, "position"},
                             {Fixed::X, "x"},
                             {Fixed::Y, "y"},
                             {Fixed::Z, "z"},
                             {Fixed::Orientation, "orientation"},
                             {Fixed::OpeningAngle, "opening_angle"}};

template <typename E>
const std::string& name_of(E value, const Names<E>& names) {
  for (const auto& [v, name] : names)
    if (v == value) return name;
  throw std::logic_error("enum value without a name");
}

// ---------------------------------------------------------------------------
// Sections

// With a `base` (an element of "rods"), every key is optional and inherited
// from it; without, width and height are required.
CrossSectionConfig read_cross_section(const JsonField& f, const CrossSectionConfig* base) {
  f.check_keys({"shape", "width", "height"});
  CrossSectionConfig c = base ? *base : CrossSectionConfig{};
  if (auto shape = f.find("shape")) c.shape = shape->choice(kShapes);
  if (auto width = base ? f.find("width") : f.require("width")) c.width = positive(*width);
  if (auto height = base ? f.find("height") : f.require("height")) c.height = positive(*height);
  return c;
}

MaterialConfig read_material(const JsonField& f, const MaterialConfig* base) {
  f.check_keys({"young_modulus", "poisson_ratio", "density", "strength", "cross_section"});
  MaterialConfig m = base ? *base : MaterialConfig{};
  if (auto e = base ? f.find("young_modulus") : f.require("young_modulus"))
    m.young_modulus = positive(*e);
  if (auto nu = f.find("poisson_ratio")) m.poisson_ratio = inside(*nu, -1, 0.5, "(-1, 0.5)");
  if (auto rho = f.find("density")) m.density = non_negative(*rho);
  if (auto strength = f.find("strength")) m.strength = positive(*strength);
  if (auto section = base ? f.find("cross_section") : f.require("cross_section"))
    m.cross_section = read_cross_section(*section, base ? &base->cross_section : nullptr);
  return m;
}

// "rest_lengths": a non-empty array of positive lengths (their count is
// checked against the linkage in make_problem_setup).
std::vector<double> read_rest_lengths(const JsonField& f) {
  std::vector<double> lengths;
  for (const JsonField& item : f.elements()) lengths.push_back(positive(item));
  if (lengths.empty())
    f.fail("must list one rest length per segment (edge of the linkage file), got an empty array");
  return lengths;
}

std::vector<RodMaterial> read_rods(const JsonField& f, const MaterialConfig& base) {
  std::vector<RodMaterial> rods;
  for (const JsonField& item : f.elements()) {
    item.check_keys({"rod", "edges", "vertices", "material"});
    RodMaterial r;
    const auto rod = item.find("rod");
    const auto edges = item.find("edges");
    const auto vertices = item.find("vertices");
    if ((rod ? 1 : 0) + (edges ? 1 : 0) + (vertices ? 1 : 0) != 1)
      item.fail("needs exactly one selector of \"rod\", \"edges\" and \"vertices\"");
    if (rod) {
      r.selector = RodSelector::Rod;
      r.rod = rod->integer();
      if (r.rod < 0)
        rod->fail("a rod index is 0-based and must be >= 0, got " + std::to_string(r.rod));
    } else if (edges) {
      r.selector = RodSelector::Edges;
      for (const JsonField& edge : edges->elements()) {
        const std::vector<JsonField> ends = edge.elements();
        if (ends.size() != 2)
          edge.fail("expected an edge [i, j] of two vertex indices, got an array of " +
                    std::to_string(ends.size()));
        const std::array<int, 2> e = {vertex_index(ends[0]), vertex_index(ends[1])};
        for (const auto& earlier : r.edges)
          if ((earlier[0] == e[0] && earlier[1] == e[1]) ||
              (earlier[0] == e[1] && earlier[1] == e[0]))
            edge.fail("edge [" + std::to_string(e[0]) + ", " + std::to_string(e[1]) +
                      "] is listed twice");
        r.edges.push_back(e);
      }
      if (r.edges.empty()) edges->fail("must list at least one edge [i, j]");
    } else {
      r.selector = RodSelector::Vertices;
      for (const JsonField& vertex : vertices->elements()) {
        const int v = vertex_index(vertex);
        if (std::find(r.vertices.begin(), r.vertices.end(), v) != r.vertices.end())
          vertex.fail("vertex " + std::to_string(v) + " is listed twice");
        r.vertices.push_back(v);
      }
      if (r.vertices.empty()) vertices->fail("must list at least one vertex");
    }
    r.material = read_material(item.require("material"), &base);
    rods.push_back(r);
  }
  return rods;
}

// Whether support `s` holds position component c (0, 1, 2: x, y, z).
bool holds(const Support& s, int c) {
  const Fixed roller = c == 0 ? Fixed::X : c == 1 ? Fixed::Y : Fixed::Z;
  return std::find(s.fix.begin(), s.fix.end(), Fixed::Position) != s.fix.end() ||
         std::find(s.fix.begin(), s.fix.end(), roller) != s.fix.end();
}

// Two entries for one vertex that hold the same position component at
// different displacements: which one wins would be an accident of order.
// Entries that "select" their vertices are compared once resolved
// (problem_setup.cpp).
void check_conflicts(const JsonField& item, const Support& s, const std::vector<Support>& earlier,
                     const std::string& list_path) {
  if (s.select) return;
  for (std::size_t i = 0; i < earlier.size(); ++i) {
    if (earlier[i].select || earlier[i].vertex != s.vertex) continue;
    if (const int c = conflicting_component(earlier[i], s); c >= 0)
      item.fail(
          support_conflict(s.vertex, list_path + "[" + std::to_string(i) + "]", earlier[i], s, c));
  }
}

std::vector<Support> read_supports(const JsonField& f) {
  std::vector<Support> supports;
  for (const JsonField& item : f.elements()) {
    item.check_keys({"vertex", "select", "fix", "displacement"});
    Support s;
    const auto vertex = item.find("vertex");
    const auto select = item.find("select");
    if (!vertex && !select) item.require("vertex");  // "missing required key"
    if (vertex && select) item.fail("needs one of \"vertex\" and \"select\", not both");
    if (vertex)
      s.vertex = vertex_index(*vertex);
    else
      s.select = read_select(*select);
    const JsonField fix = item.require("fix");
    for (const JsonField& entry : fix.elements()) {
      const Fixed what = entry.choice(kFixed);
      if (std::find(s.fix.begin(), s.fix.end(), what) != s.fix.end())
        entry.fail("\"" + name_of(what, kFixed) + "\" is listed twice");
      s.fix.push_back(what);
    }
    if (s.fix.empty())
      fix.fail(
          "must list at least one of \"position\", \"x\", \"y\", \"z\", "
          "\"orientation\", \"opening_angle\"");
    if (auto displacement = item.find("displacement")) {
      s.displacement = displacement->vector3();
      const std::vector<JsonField> components = displacement->elements();
      for (int c = 0; c < 3; ++c) {
        const Fixed roller = c == 0 ? Fixed::X : c == 1 ? Fixed::Y : Fixed::Z;
        const bool held = std::find(s.fix.begin(), s.fix.end(), Fixed::Position) != s.fix.end() ||
                          std::find(s.fix.begin(), s.fix.end(), roller) != s.fix.end();
        if (s.displacement[c] != 0.0 && !held)
          components[c].fail(
              "moves the " + name_of(roller, kFixed) +
              " component, which this support leaves free; only held components can be "
              "displaced: add \"position\" or \"" +
              name_of(roller, kFixed) + "\" to fix, or give 0");
      }
    }
    check_conflicts(item, s, supports, f.path());
    supports.push_back(s);
  }
  return supports;
}

Loads read_loads(const JsonField& f) {
  f.check_keys({"gravity", "forces", "line_loads"});
  Loads loads;
  if (auto g = f.find("gravity")) loads.gravity = g->vector3();
  if (auto forces = f.find("forces"))
    for (const JsonField& item : forces->elements()) {
      item.check_keys({"vertex", "force"});
      loads.forces.push_back(
          {vertex_index(item.require("vertex")), item.require("force").vector3()});
    }
  if (auto line_loads = f.find("line_loads"))
    for (const JsonField& item : line_loads->elements())
      loads.line_loads.push_back(read_line_load(item));
  return loads;
}

SolverOptions read_solver(const JsonField& f) {
  f.check_keys({"method", "gradient_tolerance", "max_iterations", "line_search", "mass", "damping",
                "first_order", "start", "max_steps", "escape_saddles", "buckling_direction"});
  SolverOptions s;
  if (auto method = f.find("method")) s.method = method->choice(kMethods);
  if (auto tol = f.find("gradient_tolerance")) s.gradient_tolerance = positive(*tol);
  if (auto n = f.find("max_iterations")) s.max_iterations = at_least(*n, 1);
  if (auto ls = f.find("line_search")) s.line_search = ls->choice(kLineSearches);
  if (auto mass = f.find("mass")) s.mass = mass->choice(kMasses);
  if (auto damping = f.find("damping")) {
    if (damping->is_string() && damping->string() == "auto")
      s.damping.reset();
    else if (damping->value().is_number())
      s.damping = non_negative(*damping);
    else
      damping->fail("expected a number >= 0 or \"auto\", got " + damping->describe());
  }
  if (auto first_order = f.find("first_order")) s.first_order = first_order->boolean();
  if (auto start = f.find("start")) s.start = start->choice(kStarts);
  if (auto n = f.find("max_steps")) s.max_steps = at_least(*n, 1);
  if (auto escape = f.find("escape_saddles")) s.escape_saddles = escape->boolean();
  if (auto direction = f.find("buckling_direction")) {
    s.buckling_direction = direction->vector3();
    if (!(s.buckling_direction.norm() > 0.0))
      direction->fail("expected a non-zero direction [x, y, z], got one of length 0");
  }
  return s;
}

OutputOptions read_output(const JsonField* f, const std::string& base_dir) {
  OutputOptions o;
  o.directory = resolve("out", base_dir);
  if (!f) return o;
  f->check_keys({"directory", "every", "max_steps", "format", "compression", "solids", "progress"});
  if (auto dir = f->find("directory")) o.directory = file_path(*dir, base_dir);
  if (auto every = f->find("every")) o.every = at_least(*every, 1);
  if (auto max_steps = f->find("max_steps")) {
    o.max_steps = at_least(*max_steps, 0);
    if (o.max_steps == 1) max_steps->fail("must be 0 (no limit) or at least 2, got 1");
  }
  if (auto format = f->find("format")) o.format = format->choice(kFormats);
  if (auto compression = f->find("compression")) o.compression = compression->choice(kCompressions);
  if (auto solids = f->find("solids")) o.solids = toggle(*solids);
  if (auto progress = f->find("progress")) o.progress = toggle(*progress);
  return o;
}

AnalysisOptions read_analysis(const JsonField& f) {
  f.check_keys({"modes", "buckling", "max_seconds"});
  AnalysisOptions a;
  if (auto modes = f.find("modes")) a.modes = at_least(*modes, 0);
  if (auto buckling = f.find("buckling")) a.buckling = buckling->boolean();
  if (auto seconds = f.find("max_seconds"))
    a.max_seconds = seconds->is_null() ? std::nullopt : std::optional<double>(positive(*seconds));
  return a;
}

Deployment read_deployment(const JsonField& f) {
  f.check_keys({"average_opening_angle", "joint_angles", "steps", "largest_step"});
  Deployment d;
  const auto average = f.find("average_opening_angle");
  const auto joints = f.find("joint_angles");
  if (average && joints)
    f.fail("gives both \"average_opening_angle\" and \"joint_angles\"; give only one");
  if (!average && !joints)
    f.fail("needs \"average_opening_angle\" or \"joint_angles\" (exactly one of them)");
  if (average) {
    d.target = DeploymentTarget::AverageOpeningAngle;
    d.average_opening_angle = angle(*average);
  } else {
    d.target = DeploymentTarget::JointAngles;
    for (const JsonField& item : joints->elements()) {
      item.check_keys({"vertex", "angle"});
      const JsonField vertex = item.require("vertex");
      const JointAngle a{vertex_index(vertex), angle(item.require("angle"))};
      for (const JointAngle& earlier : d.joint_angles)
        if (earlier.vertex == a.vertex)
          vertex.fail("vertex " + std::to_string(a.vertex) + " is listed twice");
      d.joint_angles.push_back(a);
    }
    if (d.joint_angles.empty()) joints->fail("must list at least one joint");
  }
  if (auto steps = f.find("steps")) d.steps = at_least(*steps, 1);
  if (auto largest = f.find("largest_step")) d.largest_step = positive(*largest);
  return d;
}

// "units": names for labels.
UnitNames read_units(const JsonField& f) {
  f.check_keys({"length", "force"});
  UnitNames names;
  for (auto [key, name] : {std::pair{"length", &names.length}, std::pair{"force", &names.force}}) {
    const auto field = f.find(key);
    if (!field) continue;
    *name = field->string();
    const bool plain = std::all_of(name->begin(), name->end(), [](char c) {
      return static_cast<unsigned char>(c) > ' ' && c != 0x7f &&
             std::string("/^[]").find(c) == std::string::npos;
    });
    if (name->empty() || name->size() > 16 || !plain)
      field->fail(
          "must be a unit's name of 1 to 16 characters without spaces, '/', '^', '[' or ']', got "
          "\"" +
          printable(*name) + "\"");
  }
  return names;
}

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json toggle_json(Toggle t) {
  if (t == Toggle::Auto) return "auto";
  return t == Toggle::On;
}

}  // namespace

Config parse_config(const std::string& text, const std::string& name, const std::string& base_dir) {
  const std::string shown = printable(name);  // the name as messages quote it
  const nlohmann::json document = parse_json(text, shown);
  const JsonField root(document, "", shown);
  if (!document.is_object())
    root.fail("the configuration must be a JSON object { ... }, got " + root.describe());
  root.check_keys({"linkage", "subdivisions", "rest_shape", "rest_lengths", "joints", "material",
                   "rods", "supports", "loads", "solver", "output", "deployment", "transform",
                   "units", "analysis", "design"});
  Config c;
  c.source = shown;
  c.linkage = file_path(root.require("linkage"), base_dir);
  if (auto transform = root.find("transform")) c.transform = read_transform(*transform);
  if (auto n = root.find("subdivisions")) c.subdivisions = at_least(*n, 3);
  if (auto rest = root.find("rest_shape")) c.rest_shape = rest->choice(kRestShapes);
  if (auto lengths = root.find("rest_lengths")) c.rest_lengths = read_rest_lengths(*lengths);
  if (auto joints = root.find("joints")) c.joints = joints->choice(kJointModels);
  c.material = read_material(root.require("material"), nullptr);
  if (auto rods = root.find("rods")) c.rods = read_rods(*rods, c.material);
  if (auto supports = root.find("supports")) c.supports = read_supports(*supports);
  if (auto loads = root.find("loads")) c.loads = read_loads(*loads);
  if (auto solver = root.find("solver")) c.solver = read_solver(*solver);
  const auto output = root.find("output");
  c.output = read_output(output ? &*output : nullptr, base_dir);
  if (auto deployment = root.find("deployment")) c.deployment = read_deployment(*deployment);
  if (auto units = root.find("units")) c.units = read_units(*units);
  if (auto analysis = root.find("analysis")) c.analysis = read_analysis(*analysis);
  if (auto design = root.find("design")) c.design = read_design(*design, base_dir);
  return c;
}

Config read_config(const std::string& path) {
  const std::string text = read_input_file(
      path, kConfigurationFile, "cannot open configuration file '" + printable(path) + "'");
  return parse_config(text, path, std::filesystem::path(path).parent_path().string());
}

void check_vertices(const Config& config, const LineGraph& graph) {
  const int n = static_cast<int>(graph.vertices.size());
  auto check = [&](int vertex, const std::string& key) {
    if (vertex < n) return;
    throw InputError(config.source + ": " + key + ": vertex " + std::to_string(vertex) +
                     " is out of range; the linkage has " + std::to_string(n) +
                     " vertices (0-based indices 0 to " + std::to_string(n - 1) + ")");
  };
  for (std::size_t i = 0; i < config.supports.size(); ++i) {
    const std::string key = "supports[" + std::to_string(i) + "]";
    const Support& s = config.supports[i];
    if (!s.select)
      check(s.vertex, key + ".vertex");
    else if (s.select->kind == SelectKind::Vertices)
      for (std::size_t k = 0; k < s.select->vertices.size(); ++k)
        check(s.select->vertices[k], key + ".select[" + std::to_string(k) + "]");
  }
  for (std::size_t i = 0; i < config.loads.forces.size(); ++i)
    check(config.loads.forces[i].vertex, "loads.forces[" + std::to_string(i) + "].vertex");
  for (std::size_t i = 0; i < config.rods.size(); ++i) {
    const std::string key = "rods[" + std::to_string(i) + "]";
    for (std::size_t k = 0; k < config.rods[i].vertices.size(); ++k)
      check(config.rods[i].vertices[k], key + ".vertices[" + std::to_string(k) + "]");
    for (std::size_t k = 0; k < config.rods[i].edges.size(); ++k)
      for (int m = 0; m < 2; ++m)
        check(config.rods[i].edges[k][m],
              key + ".edges[" + std::to_string(k) + "][" + std::to_string(m) + "]");
  }
  if (config.deployment)
    for (std::size_t i = 0; i < config.deployment->joint_angles.size(); ++i)
      check(config.deployment->joint_angles[i].vertex,
            "deployment.joint_angles[" + std::to_string(i) + "].vertex");
}

namespace {
nlohmann::json material_json(const MaterialConfig& m) {
  nlohmann::json material = {{"young_modulus", m.young_modulus},
                             {"poisson_ratio", m.poisson_ratio},
                             {"density", m.density},
                             {"cross_section",
                              {{"shape", name_of(m.cross_section.shape, kShapes)},
                               {"width", m.cross_section.width},
                               {"height", m.cross_section.height}}}};
  if (m.strength) material["strength"] = *m.strength;
  return material;
}

nlohmann::json config_rods_json(const std::vector<RodMaterial>& rods) {
  nlohmann::json out = nlohmann::json::array();
  for (const RodMaterial& r : rods) {
    nlohmann::json item = {{"material", material_json(r.material)}};
    if (r.selector == RodSelector::Rod) item["rod"] = r.rod;
    if (r.selector == RodSelector::Edges) item["edges"] = r.edges;
    if (r.selector == RodSelector::Vertices) item["vertices"] = r.vertices;
    out.push_back(item);
  }
  return out;
}

nlohmann::json config_supports_json(const std::vector<Support>& supports) {
  nlohmann::json out = nlohmann::json::array();
  for (const Support& s : supports) {
    nlohmann::json fix = nlohmann::json::array();
    for (Fixed f : s.fix) fix.push_back(name_of(f, kFixed));
    nlohmann::json item = {{"fix", fix}, {"displacement", vector_json(s.displacement)}};
    if (s.select)
      item["select"] = select_json(*s.select);
    else
      item["vertex"] = s.vertex;
    out.push_back(item);
  }
  return out;
}

nlohmann::json config_loads_json(const Loads& loads) {
  nlohmann::json forces = nlohmann::json::array();
  for (const PointForce& f : loads.forces)
    forces.push_back({{"vertex", f.vertex}, {"force", vector_json(f.force)}});
  nlohmann::json line_loads = nlohmann::json::array();
  for (const LineLoadConfig& l : loads.line_loads) line_loads.push_back(line_load_json(l));
  return {{"gravity", vector_json(loads.gravity)}, {"forces", forces}, {"line_loads", line_loads}};
}

nlohmann::json config_solver_json(const SolverOptions& s) {
  return {{"method", name_of(s.method, kMethods)},
          {"gradient_tolerance", s.gradient_tolerance},
          {"max_iterations", s.max_iterations},
          {"line_search", name_of(s.line_search, kLineSearches)},
          {"mass", name_of(s.mass, kMasses)},
          {"damping", s.damping ? nlohmann::json(*s.damping) : nlohmann::json("auto")},
          {"first_order", s.first_order},
          {"start", name_of(s.start, kStarts)},
          {"max_steps", s.step_limit()},
          {"escape_saddles", s.escape_saddles},
          {"buckling_direction", vector_json(s.buckling_direction)}};
}

nlohmann::json config_output_json(const OutputOptions& o) {
  return {{"directory", o.directory},
          {"every", o.every},
          {"max_steps", o.max_steps},
          {"format", name_of(o.format, kFormats)},
          {"compression", name_of(o.compression, kCompressions)},
          {"solids", toggle_json(o.solids)},
          {"progress", toggle_json(o.progress)}};
}

nlohmann::json config_deployment_json(const Deployment& d) {
  nlohmann::json deployment = {{"steps", d.steps}};
  if (d.largest_step > 0.0) deployment["largest_step"] = d.largest_step;
  if (d.target == DeploymentTarget::AverageOpeningAngle) {
    deployment["average_opening_angle"] = d.average_opening_angle;
  } else {
    deployment["joint_angles"] = nlohmann::json::array();
    for (const JointAngle& a : d.joint_angles)
      deployment["joint_angles"].push_back({{"vertex", a.vertex}, {"angle", a.angle}});
  }
  return deployment;
}
}  // namespace

int conflicting_component(const Support& a, const Support& b) {
  for (int c = 0; c < 3; ++c)
    if (holds(a, c) && holds(b, c) && a.displacement[c] != b.displacement[c]) return c;
  return -1;
}

std::string support_conflict(int vertex, const std::string& earlier_key, const Support& earlier,
                             const Support& later, int c) {
  std::ostringstream values;
  values.precision(12);
  values << earlier.displacement[c] << " and " << later.displacement[c];
  return "vertex " + std::to_string(vertex) + " is also held by " + earlier_key +
         ", and the two displace its " + "xyz"[c] + " component differently (" + values.str() +
         "); give one displacement per vertex (one entry, or equal displacements)";
}

nlohmann::json to_json(const Config& c) {
  nlohmann::json j = {{"linkage", c.linkage},
                      {"subdivisions", c.subdivisions},
                      {"rest_shape", name_of(c.rest_shape, kRestShapes)},
                      {"joints", name_of(c.joints, kJointModels)},
                      {"material", material_json(c.material)},
                      {"rods", config_rods_json(c.rods)},
                      {"supports", config_supports_json(c.supports)},
                      {"loads", config_loads_json(c.loads)},
                      {"solver", config_solver_json(c.solver)},
                      {"output", config_output_json(c.output)},
                      {"analysis",
                       {{"modes", c.analysis.modes},
                        {"buckling", c.analysis.buckling},
                        {"max_seconds", optional_json(c.analysis.max_seconds)}}}};
  if (!c.transform.is_identity()) j["transform"] = transform_json(c.transform);
  if (!c.rest_lengths.empty()) j["rest_lengths"] = c.rest_lengths;
  if (!c.units.length.empty()) j["units"]["length"] = c.units.length;
  if (!c.units.force.empty()) j["units"]["force"] = c.units.force;
  if (c.deployment) j["deployment"] = config_deployment_json(*c.deployment);
  if (c.design) j["design"] = design_json(*c.design);
  return j;
}

}  // namespace xshell
