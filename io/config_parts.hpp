// Readers and writers of three objects of the configuration (config.hpp):
// "transform", "supports[].select" and "loads.line_loads[]", and the message
// for two supports that displace one vertex differently. Each reader checks
// its value as config.cpp's do, throwing InputError with the JSON path.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "config.hpp"
#include "json_field.hpp"

namespace xshell {

GraphTransform read_transform(const JsonField& f);
nlohmann::json transform_json(const GraphTransform& t);

SupportSelect read_select(const JsonField& f);
nlohmann::json select_json(const SupportSelect& s);

LineLoadConfig read_line_load(const JsonField& f);
nlohmann::json line_load_json(const LineLoadConfig& l);

// "vertex V is also held by EARLIER_KEY, and the two displace its x component
// differently (...)": supports `earlier` and `later` at `vertex`, component c.
std::string support_conflict(int vertex, const std::string& earlier_key, const Support& earlier,
                             const Support& later, int c);

}  // namespace xshell
