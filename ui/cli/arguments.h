#pragma once
// Argument parsing helpers shared by the commands.

#include <CLI/Error.hpp>  // Validators.hpp uses it without including it
#include <CLI/Validators.hpp>
#include <Eigen/Core>
#include <string>
#include <vector>

namespace plumb::cli {

// "X,Y,Z" as three finite numbers. Throws plumb::Error naming `option` otherwise.
Eigen::Vector3d parseVector3(const std::string& text, const std::string& option);

// Finite numbers separated by commas, `least` to `most` of them. Throws plumb::Error naming
// `option` and showing `example` otherwise.
std::vector<double> parseNumbers(const std::string& text, std::size_t least, std::size_t most,
                                 const std::string& option, const std::string& example);

// A CLI11 check: a finite number in [min, max] (CLI::Range lets NaN through).
CLI::Validator finiteIn(double min, double max);

// 1234567 -> "1,234,567".
std::string withThousands(std::uint64_t value);

// Whether two paths name the same file, existing or not (an output must not overwrite an input).
bool sameFile(const std::string& a, const std::string& b);

}  // namespace plumb::cli
