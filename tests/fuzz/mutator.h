#pragma once
// The replay's mutations (fuzz_replay_main.cpp): a deterministic stream of malformed variants of
// a seed corpus, in the manner of libFuzzer's mutators but without coverage feedback.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/core/random.h"

namespace plumb::fuzz {

using Input = std::vector<std::uint8_t>;

class Mutator {
 public:
  // `seeds` must not be empty; they are kept by reference and must outlive the mutator. The
  // stream depends only on the seeds (contents and order) and `random_seed`.
  Mutator(const std::vector<Input>& seeds, std::uint64_t random_seed);

  // The next input: a seed (or, one time in four, the previous input) with one to four
  // mutations: bit flips, bytes and little-endian integers set to boundary values, numbers
  // and JSON tokens written over text, truncation, erased, duplicated and random chunks, and the
  // head of one input spliced to the tail of another. Valid until the next call.
  const Input& next();

 private:
  void mutateOnce(Input& input);

  const std::vector<Input>& seeds_;
  Random random_;
  Input current_;
};

}  // namespace plumb::fuzz
