#include "io/fabrication_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/xml_text.hpp"

namespace xshell {

namespace {

// Layout, in px.
constexpr double kLongest = 1000.0;  // drawn length of the longest lath
constexpr double kLeft = 80.0;       // room for the lath numbers
constexpr double kRight = 140.0;     // room for the lengths
constexpr double kTop = 56.0;        // room for the title
constexpr double kLabel = 13.0;      // a line of hole numbers, above and below a lath
constexpr double kGap = 10.0;        // between rows
constexpr double kMinWidth = 6.0;    // thinnest lath drawn
constexpr double kBottom = 60.0;     // room for the scale bar

const char* fill_of(RodFamily family) { return family == RodFamily::A ? "#f2d7a0" : "#c9ddf2"; }

std::string px(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", value);
  return buffer;
}

// A length for people: 6 significant digits.
std::string length_text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

// The largest 1, 2 or 5 times a power of ten not above `limit` (> 0).
double nice_length(double limit) {
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * decade <= limit) return m * decade;
  return decade;
}

struct Layout {
  double scale = 1.0;       // px per length unit
  double lath = kMinWidth;  // band of a row's lath: the widest lath drawn
  double row = 0.0;         // row pitch
};

std::string lath_svg(const FabricationRod& rod, const Layout& layout, double top) {
  // The row's band fits the widest lath; this one is centred in it.
  const double y = top + kLabel, mid = y + 0.5 * layout.lath;
  const double width = rod.length * layout.scale;
  const double thickness = std::max(kMinWidth, rod.section.width * layout.scale);
  const double hole = std::clamp(0.3 * thickness, 1.5, 5.0);
  std::string out = "<g class=\"lath\" data-rod=\"" + std::to_string(rod.rod) +
                    "\" data-family=\"" + family_name(rod.family) + "\" data-length=\"" +
                    length_text(rod.length) + "\">\n";
  out += "<rect x=\"" + px(kLeft) + "\" y=\"" + px(mid - 0.5 * thickness) + "\" width=\"" +
         px(width) + "\" height=\"" + px(thickness) + "\" fill=\"" + fill_of(rod.family) +
         "\" stroke=\"#333\" stroke-width=\"0.8\"/>\n";
  out += "<text class=\"rod-number\" x=\"" + px(kLeft - 8.0) + "\" y=\"" + px(mid + 4.0) +
         "\" text-anchor=\"end\" font-size=\"12\" font-weight=\"bold\">" + std::to_string(rod.rod) +
         " " + family_name(rod.family) + "</text>\n";
  out += "<text x=\"" + px(kLeft + width + 8.0) + "\" y=\"" + px(mid + 4.0) +
         "\" font-size=\"11\">L = " + length_text(rod.length) + (rod.closed ? " (closed)" : "") +
         "</text>\n";
  int k = 0;
  for (const RodStation& st : rod.stations) {
    if (st.kind != StationKind::Joint) continue;
    const double x = kLeft + st.s * layout.scale;
    // Numbers alternate above and below the lath so that close holes stay
    // readable.
    const double label_y = (k++ % 2 == 0) ? y - 3.0 : y + layout.lath + kLabel - 3.0;
    out += "<circle class=\"hole\" cx=\"" + px(x) + "\" cy=\"" + px(mid) + "\" r=\"" + px(hole) +
           "\" fill=\"#fff\" stroke=\"#000\" stroke-width=\"0.8\" data-rod=\"" +
           std::to_string(rod.rod) + "\" data-vertex=\"" + std::to_string(st.vertex) +
           "\" data-s=\"" + length_text(st.s) + "\"><title>rod " + std::to_string(rod.rod) +
           ", vertex " + std::to_string(st.vertex) + ", s = " + length_text(st.s) +
           "</title></circle>\n";
    out += "<text class=\"hole-number\" x=\"" + px(x) + "\" y=\"" + px(label_y) +
           "\" text-anchor=\"middle\" font-size=\"9\">" + std::to_string(st.vertex) + "</text>\n";
  }
  out += "</g>\n";
  return out;
}

std::string scale_bar_svg(const Layout& layout, double longest, double top,
                          const std::string& unit) {
  const double bar = nice_length(0.25 * longest);
  const double x0 = kLeft, x1 = kLeft + bar * layout.scale, y = top + 20.0;
  std::string out = "<g class=\"scale-bar\">\n";
  out += "<line x1=\"" + px(x0) + "\" y1=\"" + px(y) + "\" x2=\"" + px(x1) + "\" y2=\"" + px(y) +
         "\" stroke=\"#000\" stroke-width=\"2\"/>\n";
  for (double x : {x0, x1})
    out += "<line x1=\"" + px(x) + "\" y1=\"" + px(y - 5.0) + "\" x2=\"" + px(x) + "\" y2=\"" +
           px(y + 5.0) + "\" stroke=\"#000\" stroke-width=\"1.5\"/>\n";
  out += "<text x=\"" + px(x1 + 8.0) + "\" y=\"" + px(y + 4.0) + "\" font-size=\"12\">" +
         length_text(bar) + " (" + xml_escaped(unit) + ")</text>\n";
  out += "</g>\n";
  return out;
}

}  // namespace

std::string fabrication_svg(const FabricationData& data, const FabricationUnits& units) {
  double longest = 0.0, widest = 0.0;
  int family_a = 0;
  for (const FabricationRod& rod : data.rods) {
    longest = std::max(longest, rod.length);
    widest = std::max(widest, rod.section.width);
    family_a += rod.family == RodFamily::A;
  }
  if (!(longest > 0.0)) longest = 1.0;  // no rods: an empty drawing
  Layout layout;
  layout.scale = kLongest / longest;
  layout.lath = std::max(kMinWidth, widest * layout.scale);
  layout.row = kLabel + layout.lath + kLabel + kGap;
  const double rows_end = kTop + layout.row * static_cast<double>(data.rods.size());
  const double width = kLeft + kLongest + kRight, height = rows_end + kBottom;

  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + px(width) + "\" height=\"" +
         px(height) + "\" viewBox=\"0 0 " + px(width) + " " + px(height) +
         "\" font-family=\"sans-serif\">\n";
  out += "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  out += "<text x=\"" + px(kLeft) + "\" y=\"22\" font-size=\"15\" font-weight=\"bold\">" +
         std::to_string(data.rods.size()) + " laths (" + std::to_string(family_a) + " A, " +
         std::to_string(data.rods.size() - family_a) + " B), " +
         std::to_string(data.joints.size()) + " joints; lengths in " + xml_escaped(units.length) +
         "</text>\n";
  out += "<text x=\"" + px(kLeft) +
         "\" y=\"40\" font-size=\"11\">Each lath runs from s = 0 "
         "(left) to its cut length L; holes at the joint stations, numbered by OBJ vertex "
         "(0-based): pin equal numbers together.</text>\n";
  for (size_t r = 0; r < data.rods.size(); ++r)
    out += lath_svg(data.rods[r], layout, kTop + layout.row * static_cast<double>(r));
  out += scale_bar_svg(layout, longest, rows_end, units.length);
  out += "</svg>\n";
  return out;
}

}  // namespace xshell
