#include "core/memory_sources.h"

#include <sys/resource.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>

namespace glint {

namespace {

std::string_view trimmed(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

std::optional<uint64_t> number(std::string_view s) {
  s = trimmed(s);
  uint64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

std::vector<std::string_view> split(std::string_view s, char separator) {
  std::vector<std::string_view> parts;
  for (size_t at = 0;;) {
    const size_t next = s.find(separator, at);
    parts.push_back(s.substr(at, next == std::string_view::npos ? next : next - at));
    if (next == std::string_view::npos) return parts;
    at = next + 1;
  }
}

// The value of "KEY:   N kB" in a /proc file of such lines, in bytes.
std::optional<uint64_t> kilobytesOf(std::string_view text, std::string_view key) {
  for (std::string_view line : split(text, '\n')) {
    if (line.substr(0, key.size()) != key) continue;
    std::string_view value = trimmed(line.substr(key.size()));
    if (value.size() < 2 || value.substr(value.size() - 2) != "kB") return std::nullopt;
    const auto kb = number(value.substr(0, value.size() - 2));
    if (!kb || *kb > UINT64_MAX / 1024) return std::nullopt;
    return *kb * 1024;
  }
  return std::nullopt;
}

// mountinfo writes a space in a path as \040 (and tab, newline, backslash likewise).
std::string unescaped(std::string_view field) {
  std::string out;
  for (size_t i = 0; i < field.size(); ++i) {
    const auto octal = [&](size_t k) { return field[k] >= '0' && field[k] <= '7'; };
    if (field[i] == '\\' && i + 3 < field.size() && octal(i + 1) && octal(i + 2) && octal(i + 3)) {
      out += char((field[i + 1] - '0') * 64 + (field[i + 2] - '0') * 8 + (field[i + 3] - '0'));
      i += 3;
    } else {
      out += field[i];
    }
  }
  return out;
}

// `dir` (the cgroup `path` under a mount of `root` at `mountPoint`) and its ancestors up to
// the mount point.
void appendWithAncestors(std::vector<CgroupDir>& dirs, const std::string& mountPoint,
                         const std::string& root, std::string path, bool v2) {
  // Outside the mount's root (a cgroup namespace shows its own root as "/"): the mount point
  // is the closest directory that can be read.
  if (root != "/") {
    if (path.compare(0, root.size(), root) == 0 &&
        (path.size() == root.size() || path[root.size()] == '/'))
      path = path.substr(root.size());
    else
      path.clear();
  }
  while (!path.empty() && path.back() == '/') path.pop_back();
  for (;;) {
    dirs.push_back({mountPoint + path, v2});
    if (path.empty()) return;
    path.erase(path.rfind('/'));
  }
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

MemoryBudget memoryBudget(const MemoryReadings& r) {
  MemoryBudget budget;
  const auto consider = [&](uint64_t bytes, MemoryLimit source) {
    bytes = std::max<uint64_t>(bytes, 1);
    if (budget.limitedBy == MemoryLimit::Unknown || bytes < budget.bytes) budget = {bytes, source};
  };
  if (r.available) consider(*r.available, MemoryLimit::Available);
  if (r.addressSpaceLimit)
    consider(
        *r.addressSpaceLimit > r.addressSpaceUsed ? *r.addressSpaceLimit - r.addressSpaceUsed : 0,
        MemoryLimit::AddressSpace);
  if (r.cgroupHeadroom) consider(*r.cgroupHeadroom, MemoryLimit::Cgroup);
  return budget;
}

std::optional<uint64_t> parseMemAvailable(std::string_view meminfo) {
  return kilobytesOf(meminfo, "MemAvailable:");
}

std::optional<uint64_t> parseVmSize(std::string_view status) {
  return kilobytesOf(status, "VmSize:");
}

std::vector<CgroupDir> memoryCgroupDirs(std::string_view cgroup, std::string_view mountinfo) {
  // The mounts: (mount point, root) of the cgroup2 mount and of the v1 memory controller's.
  struct Mount {
    std::string point, root;
  };
  std::optional<Mount> v2Mount, v1Mount;
  for (std::string_view line : split(mountinfo, '\n')) {
    const std::vector<std::string_view> f = split(trimmed(line), ' ');
    const auto dash = std::find(f.begin(), f.end(), "-");
    if (f.size() < 5 || dash == f.end() || f.end() - dash < 4) continue;
    const std::string_view type = dash[1];
    const Mount m{unescaped(f[4]), unescaped(f[3])};
    if (type == "cgroup2" && !v2Mount) v2Mount = m;
    if (type == "cgroup" && !v1Mount) {
      const std::vector<std::string_view> options = split(dash[3], ',');
      if (std::find(options.begin(), options.end(), "memory") != options.end()) v1Mount = m;
    }
  }
  std::vector<CgroupDir> dirs;
  std::optional<std::string> v2Path, v1Path;
  for (std::string_view line : split(cgroup, '\n')) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string_view::npos || second == std::string_view::npos) continue;
    const std::string_view id = line.substr(0, first);
    const std::string_view controllers = line.substr(first + 1, second - first - 1);
    const std::string path(trimmed(line.substr(second + 1)));
    if (path.empty() || path[0] != '/') continue;
    const std::vector<std::string_view> names = split(controllers, ',');
    if (id == "0" && controllers.empty())
      v2Path = path;
    else if (std::find(names.begin(), names.end(), "memory") != names.end())
      v1Path = path;
  }
  if (v2Mount && v2Path) appendWithAncestors(dirs, v2Mount->point, v2Mount->root, *v2Path, true);
  if (v1Mount && v1Path) appendWithAncestors(dirs, v1Mount->point, v1Mount->root, *v1Path, false);
  return dirs;
}

std::optional<uint64_t> cgroupHeadroom(std::string_view limit, std::string_view usage) {
  const auto l = number(limit), u = number(usage);
  // v1 writes "no limit" as the largest page multiple below 2^63.
  if (!l || !u || *l >= (uint64_t{1} << 62)) return std::nullopt;
  return *l > *u ? *l - *u : 0;
}

MemoryReadings readMemoryReadings() {
  MemoryReadings r;
  r.available = parseMemAvailable(readFile("/proc/meminfo"));
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    r.addressSpaceLimit = uint64_t(limit.rlim_cur);
    r.addressSpaceUsed = parseVmSize(readFile("/proc/self/status")).value_or(0);
  }
  // Where the cgroup is does not change while Glint runs; its limit and usage do.
  static const std::vector<CgroupDir> dirs =
      memoryCgroupDirs(readFile("/proc/self/cgroup"), readFile("/proc/self/mountinfo"));
  for (const CgroupDir& dir : dirs) {
    const std::string limitFile = dir.path + (dir.v2 ? "/memory.max" : "/memory.limit_in_bytes");
    const std::string usageFile =
        dir.path + (dir.v2 ? "/memory.current" : "/memory.usage_in_bytes");
    if (const auto headroom = cgroupHeadroom(readFile(limitFile), readFile(usageFile)))
      r.cgroupHeadroom = std::min(r.cgroupHeadroom.value_or(UINT64_MAX), *headroom);
  }
  return r;
}

}  // namespace glint
