#pragma once
// Options that take a fixed count of values (render --crop X0 X1 Y0 Y1, validate --ray with its
// nine numbers). CLI11 takes the count it is told whatever follows: it read
// "--crop 0 10 -o c.exr" as four values, "-o" among them, and left a fifth number to the
// positionals. The command line is checked against every such option before CLI11 reads it, and
// an occurrence with too few or too many values is refused naming the option, the values it got
// and what it takes ("--crop takes 4 integers X0 X1 Y0 Y1, got 2: 0 10").
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace glint {

enum class ValueKind { Integer, Number };

// Makes `option` (of the subcommand `command`) take exactly `count` values of `kind`, named by
// `names` ("X0 X1 Y0 Y1"), each occurrence on its own; one argument holding several values
// separated by spaces (a quoted "ox oy oz ...") counts as those values.
CLI::Option* takesValues(CLI::App& command, CLI::Option* option, int count, ValueKind kind,
                         const std::string& names);

// The command line without the program's name, checked against every option takesValues made:
// throws UsageError for an occurrence with fewer values than it takes, or with a further value
// of its kind right after them. Returns the arguments with each quoted group of values split
// into one argument per value, as CLI11 must see them.
std::vector<std::string> checkArities(const CLI::App& app, std::vector<std::string> args);

}  // namespace glint
