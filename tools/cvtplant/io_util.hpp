#pragma once
// Small shared helpers for subcommands: strict number parsing, input files
// read with a size cap, outputs whose write errors fail the run, and JSON
// printing with deterministic number formatting.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "commands.hpp"

namespace cvtcli {

// Parses a finite double or throws UsageError naming `what`.
double parse_finite(const std::string& text, const std::string& what);

// Parses "a,b,c,..." into exactly `n` finite doubles (n = 0: any count >= 1).
std::vector<double> parse_list(const std::string& text, std::size_t n, const std::string& what);

// Parses repeated "name=value" options (`--param`) into a map of finite
// doubles; a later assignment of a name replaces an earlier one. Throws
// UsageError naming `flag` (and the name, for a bad value).
std::map<std::string, double> parse_assignments(const std::vector<std::string>& items, const std::string& flag);

// Reads a whole input file of at most `max_bytes` (a regular file or a pipe;
// a directory, a device such as /dev/null or /dev/zero, or a larger input
// is a UsageError naming `what` and the path).
std::string read_input_file(const std::string& path, std::size_t max_bytes, const std::string& what);

// Opens `path` for writing ("-" = stdout) or throws UsageError naming
// `flag`: an empty path, one with a control character, a directory, or one
// that cannot be created. `inputs` are files the command reads: writing over
// one of them (the same file through any link) is refused, naming them as
// `inputs_role` ("--scene", "the shards"). A command with
// several outputs checks them all first with cvt::files::CommandFiles
// (docs/cli.md#files).
std::FILE* open_output(const std::string& path, const std::string& flag = "output",
                       const std::vector<std::string>& inputs = {}, const std::string& inputs_role = "an input");
// Refuses an input file that lies in `dir` (the same directory by device
// and inode), where a command writes files of fixed names (figures, data,
// scripts): one of them could be the input. A UsageError naming both flags.
void refuse_input_in_dir(const std::string& in_flag, const std::string& in, const std::string& dir_flag,
                         const std::string& dir);

// A generated file (a parameter file, a header, a script) written whole or
// not at all (cvt::files::replace_file); UsageError naming `flag` if it
// cannot be created, RunError if the write fails.
void write_generated_file(const std::string& path, const std::string& text, const std::string& flag);
// Whether every write to `f` so far succeeded; on the first failure the
// system's reason (EPIPE, ENOSPC) is kept for the message of close_output,
// so call it right after writing. nullptr is fine.
bool output_ok(std::FILE* f);
// Throws RunError if a write to `f` has failed (closed pipe, full disk).
void check_output(std::FILE* f);
// Flushes and closes (stdout is only flushed); a failed write is a RunError.
void close_output(std::FILE* f);
// Why the last failed write failed ("Broken pipe", "No space left on device").
std::string write_error_reason(int fresh_errno);

// Prints JSON to stdout with a trailing newline.
void print_json(const nlohmann::json& j);

// What was not computed (docs/cli.md#nulls): a value that is not finite is
// `null` in JSON and "n/a" in text, never a number made up in its place.
nlohmann::json json_number(double v);
// printf-formatted with `format` (one conversion of a double), or "n/a".
std::string text_number(double v, const char* format);

}  // namespace cvtcli
