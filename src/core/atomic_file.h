#pragma once
// Atomic file output: every writer writes to "<name>.tmp-<pid>" in the same folder and renames it
// over the final name, so a crash or a kill never leaves a half-written file under a real name.
#include <filesystem>
#include <functional>
#include <string>

namespace inet {

/// Calls write(tmp_path) and renames tmp_path to `path`. If write throws, the temporary is
/// removed and the exception propagates. Parent folders are created.
void writeFileAtomic(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path&)>& write);

/// Writes `contents` to `path` atomically.
void writeTextAtomic(const std::filesystem::path& path, const std::string& contents);

/// Removes leftover "*.tmp-*" files (from a killed run) under `dir`, recursively.
/// Returns how many were removed.
int removeStaleTemporaries(const std::filesystem::path& dir);

/// True if `name` looks like one of our temporaries.
bool isTemporaryName(const std::string& name);

/// A writable folder for our caches, created if needed: $XDG_CACHE_HOME/interiornet/<name>,
/// else ~/.cache/interiornet/<name>, else <temp>/interiornet-<name>, the first that can be
/// written. Throws InputError when none can.
std::filesystem::path userCacheDir(const std::string& name);

/// Reads a whole file; throws InputError naming the file when it cannot be read.
std::string readTextFile(const std::filesystem::path& path);

}  // namespace inet
