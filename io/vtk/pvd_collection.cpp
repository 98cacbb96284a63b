#include "pvd_collection.hpp"

#include <locale>
#include <sstream>

#include "io/xml_text.hpp"

namespace xshell {
namespace {}  // namespace

const char* part_name(VtkPart part) {
  switch (part) {
    case VtkPart::Rods:
      return "rods";
    case VtkPart::Frames:
      return "frames";
    case VtkPart::Joints:
      return "joints";
    case VtkPart::Solids:
      return "solids";
  }
  return "unknown";
}

std::string pvd_text(const std::vector<PvdEntry>& entries) {
  std::ostringstream out;
  out.imbue(std::locale::classic());  // '.' as decimal point whatever the global locale
  out.precision(17);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (const PvdEntry& entry : entries)
    out << "    <DataSet timestep=\"" << entry.timestep << "\" part=\""
        << static_cast<int>(entry.part) << "\" name=\"" << part_name(entry.part) << "\" file=\""
        << xml_escaped(entry.file) << "\"/>\n";
  out << "  </Collection>\n"
      << "</VTKFile>\n";
  return out.str();
}

}  // namespace xshell
