// The test suite's fuzz run: replays a target's seed corpus, then a fixed sequence of mutations
// of it, through the target's LLVMFuzzerTestOneInput, in any build (CI builds with GCC, which
// has no libFuzzer; the sanitizers of the build catch what libFuzzer's would). There is no
// coverage feedback, so it finds less than scripts/fuzz's long runs; what it gives is that every
// change meets thousands of malformed files under ASan and UBSan before it lands.
//
// Deterministic: the same seeds and arguments make the same inputs, in the same order, whatever
// the machine or its load (the number of inputs is fixed, never a time budget). A crash, a
// sanitizer report or a trap in the target fails the run; the last line of its output then names
// the input, and --write-input K FILE writes it out (see docs/testing.md, "Fuzzing").
//
// Usage: plumb_fuzz_replay_<target> [--iterations N] [--seed S] [--max-seed-bytes B]
//                                   [--write-input K FILE] SOURCE...
// A SOURCE is a directory (every file in it) or DIR/*SUFFIX (the files of DIR whose names end in
// SUFFIX); one that does not exist is skipped with a note (../shared need not be beside the
// clone). Seeds over B bytes (default 65536) are cut to their first B bytes. With no seed at all
// the run is skipped: exit status 77 (ctest's SKIP_RETURN_CODE).

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/fuzz/mutator.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_UNDEFINED__)
#define PLUMB_REPLAY_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define PLUMB_REPLAY_SANITIZED 1
#endif
#endif
#ifdef PLUMB_REPLAY_SANITIZED
#include <sanitizer/common_interface_defs.h>
#endif

namespace {

namespace fs = std::filesystem;

constexpr int kSkipped = 77;
using plumb::fuzz::Input;

struct Options {
  std::uint64_t iterations = 1000;
  std::uint64_t seed = 1;
  std::size_t max_seed_bytes = 65536;
  bool write_input = false;
  std::uint64_t write_index = 0;
  std::string write_path;
  std::vector<std::string> sources;
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "fuzz replay: " << why
            << "\nusage: plumb_fuzz_replay_<target> [--iterations N] [--seed S] [--max-seed-bytes B]"
               " [--write-input K FILE] SOURCE...\n";
  std::exit(2);
}

std::uint64_t number(const char* text) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0') usage(std::string("not a whole number: '") + text + "'");
  return value;
}

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&] {
      if (i + 1 >= argc) usage(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--iterations") {
      options.iterations = number(value());
    } else if (arg == "--seed") {
      options.seed = number(value());
    } else if (arg == "--max-seed-bytes") {
      options.max_seed_bytes = number(value());
    } else if (arg == "--write-input") {
      options.write_input = true;
      options.write_index = number(value());
      options.write_path = value();
    } else if (arg.starts_with("--")) {
      usage("unknown option " + arg);
    } else {
      options.sources.push_back(arg);
    }
  }
  if (options.sources.empty()) usage("no seed source");
  return options;
}

// The seeds of every source, each source's files in name order, so that the inputs do not depend
// on the order in which the file system lists them.
std::vector<Input> loadSeeds(const Options& options) {
  std::vector<Input> seeds;
  for (const std::string& source : options.sources) {
    fs::path dir = source;
    std::string suffix;
    if (const auto name = dir.filename().string(); name.starts_with("*")) {
      suffix = name.substr(1);
      dir = dir.parent_path();
    }
    if (!fs::is_directory(dir)) {
      std::cout << "skipped " << source << ": no such directory\n";
      continue;
    }
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.is_regular_file() && entry.path().filename().string().ends_with(suffix)) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
      std::ifstream in(file, std::ios::binary);
      Input bytes;
      bytes.resize(std::min<std::uintmax_t>(fs::file_size(file), options.max_seed_bytes));
      in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
      if (!in) usage("cannot read " + file.string());
      seeds.push_back(std::move(bytes));
    }
    std::cout << source << ": " << files.size() << " seeds\n";
  }
  return seeds;
}

// What runs now, for the crash handlers: a fixed buffer, since they may only call write().
char g_current[160] = "nothing yet";

void sayCurrent() {
  static volatile std::sig_atomic_t said = 0;  // a sanitizer's report may end in abort(): say it once
  if (said) return;
  said = 1;
  static const char kPrefix[] = "\nfuzz replay: stopped in input ";
  static const char kHint[] = " (rerun with --write-input to get it as a file)\n";
  (void)!::write(STDERR_FILENO, kPrefix, sizeof(kPrefix) - 1);
  (void)!::write(STDERR_FILENO, g_current, std::strlen(g_current));
  (void)!::write(STDERR_FILENO, kHint, sizeof(kHint) - 1);
}

extern "C" void onSignal(int signal) {
  sayCurrent();
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

void run(const Input& input, const char* what, std::uint64_t index) {
  std::snprintf(g_current, sizeof(g_current), "%s %llu", what, static_cast<unsigned long long>(index));
  LLVMFuzzerTestOneInput(input.data(), input.size());
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  const std::vector<Input> seeds = loadSeeds(options);
  if (seeds.empty()) {
    std::cout << "skipped: no seeds in any source\n";
    return kSkipped;
  }
  plumb::fuzz::Mutator mutator(seeds, options.seed);

  if (options.write_input) {
    // Mutation K is the K-th the mutator makes: make them all again, without running them.
    for (std::uint64_t i = 0; i < options.write_index; ++i) mutator.next();
    const Input& input = mutator.next();
    std::ofstream(options.write_path, std::ios::binary)
        .write(reinterpret_cast<const char*>(input.data()), static_cast<std::streamsize>(input.size()));
    std::cout << "wrote mutation " << options.write_index << " (" << input.size() << " bytes) to " << options.write_path
              << "\n";
    return 0;
  }

  // Say which input failed, whether the sanitizer reports it (death callback) or the process
  // aborts (an exception that is not a plumb::Error escapes the target) or traps.
#ifdef PLUMB_REPLAY_SANITIZED
  __sanitizer_set_death_callback(sayCurrent);
#endif
  // __builtin_trap is SIGILL. The sanitizers handle SIGSEGV, SIGBUS and SIGFPE themselves (and
  // call the death callback): a handler of ours would replace their report.
  for (const int signal : {SIGABRT, SIGILL}) std::signal(signal, onSignal);
#ifndef PLUMB_REPLAY_SANITIZED
  for (const int signal : {SIGSEGV, SIGBUS, SIGFPE}) std::signal(signal, onSignal);
#endif

  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t i = 0; i < seeds.size(); ++i) run(seeds[i], "seed", i);
  for (std::uint64_t i = 0; i < options.iterations; ++i) run(mutator.next(), "mutation", i);
  std::snprintf(g_current, sizeof(g_current), "none: the run is over (the leak check at exit?)");
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  std::cout << seeds.size() << " seeds and " << options.iterations << " mutations (seed " << options.seed << ") in "
            << took.count() << " s: no findings\n";
  return 0;
}
