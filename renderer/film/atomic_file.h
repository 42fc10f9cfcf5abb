#pragma once
// Writes a file so that readers see either the complete new file or the previous one: the data
// goes to a temporary file in the same directory, is fsync'ed, then renamed into place.
#include <functional>
#include <string>
#include <vector>

namespace glint {

// Throws a UsageError unless finalPath may be written: its directory exists and a file can be
// made in it (the temporary file the write would use is created and removed), and nothing is
// there or a regular file that this run did not read (core/input_files.h) and that the user may
// write (access(2): root may write any). Commands call it before rendering, so that a long
// render does not end in a refusal.
void checkOutputPath(const std::string& finalPath);

// An output a command was asked for: the option that names it ("-o", "--stats-json") and its
// path (empty: not asked for; "-": standard output).
struct NamedOutput {
  std::string option, path;
};

// Whether two paths name one file: the same path once made absolute and its directories' links
// resolved, or, for a file that exists, the same device and inode (a hard link, or a link to it).
bool nameOneFile(const std::string& a, const std::string& b);

// checkOutputPath for each output asked for, after refusing two options that name one file:
// the same path once made absolute and its directories' links resolved, or, for a file that
// exists, the same device and inode (a hard link, or a link to it), or both standard output.
// Every command calls it with all its outputs before doing any work, so that one output never
// overwrites another.
void checkOutputPaths(const std::vector<NamedOutput>& outputs);

// checkOutputPaths, then, where an output is "-", standard output kept for it alone: what the
// program prints from then on goes to standard error, so that a pipe reading the output (JSON
// into jq) gets nothing else. For a command line program; a library's host (the Python module)
// keeps its standard output and calls checkOutputPaths.
void checkCommandOutputs(const std::vector<NamedOutput>& outputs);

// Calls write(tmpPath) to produce the data, then publishes it at finalPath. On any failure the
// temporary file is removed, finalPath is left untouched, and a GlintError names the cause. A
// file it replaces keeps its permission bits, and its owner and group where the process may
// give them (a 0600 frame stays 0600); a new file gets the writer's default (0666 less umask).
// Temporary files are named ".glint-tmp-HOST-PID-N-NAME.EXT" within NAME_MAX; those of this
// host's processes that died before cleaning up are removed by a process's first write in the
// directory (once per directory and process: a sequence's frames do not each read it).
void writeFileAtomically(const std::string& finalPath,
                         const std::function<void(const std::string& tmpPath)>& write);

// The same for a text file (JSON figures, CSV); "-" writes to standard output (the one
// checkCommandOutputs kept, where it did).
void writeTextFileAtomically(const std::string& finalPath, const std::string& text);

}  // namespace glint
