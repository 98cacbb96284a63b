// Text inside XML documents (the .pvd series, fabrication.svg): the five
// characters XML reserves, replaced by their entities.
#pragma once

#include <string>

namespace xshell {

// `text` with & < > " ' written as &amp; &lt; &gt; &quot; &apos;.
std::string xml_escaped(const std::string& text);

}  // namespace xshell
