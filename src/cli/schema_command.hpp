#pragma once
/// \file schema_command.hpp  `flexgait schema`: every configuration key and every summary field,
/// derived from the records' single declarations (core/record.hpp), as JSON.
#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace flexgait::cli {

/// The document `flexgait schema` prints and `reproduce` writes as schema.json:
/// {"configurations": {command: [{key, type, default, unit, doc, allowed}, ...]},
///  "aliases": {command: [{key, parts: [key, ...], doc}, ...]} (a key that sets each of its parts),
///  "results": {file: {"fields": [{key, type, unit, doc[, choices]}, ...]}},
///  "tables": {"command: file.csv": {doc, columns: [name, ...][, present_when: {condition: [name, ...]}]}},
///  "reproduce": {run directory: command}} (the runs of `flexgait reproduce`, for the report).
std::string schema_document();

void add_schema_command(CLI::App& app, std::function<int()>& action);

}  // namespace flexgait::cli
