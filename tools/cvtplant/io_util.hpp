#pragma once
// Small shared helpers for subcommands: strict number parsing, CSV output and
// JSON printing with deterministic number formatting.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"

namespace cvtcli {

// Parses a finite double or throws UsageError naming `what`.
double parse_finite(const std::string& text, const std::string& what);

// Parses "a,b,c,..." into exactly `n` finite doubles (n = 0: any count >= 1).
std::vector<double> parse_list(const std::string& text, std::size_t n, const std::string& what);

// Opens `path` for writing ("-" = stdout) or throws UsageError.
std::FILE* open_output(const std::string& path);
void close_output(std::FILE* f);

// Prints JSON to stdout with a trailing newline.
void print_json(const nlohmann::json& j);

}  // namespace cvtcli
