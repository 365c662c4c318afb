// The fault matrix (fault_matrix.hpp) as tests: one test per case, each a whole virtual-time run in
// this process; a case fails with every way its run fell short of the expectation, and the measured
// times are in the test log. `fault_matrix_table` prints the same cases as one table.

#include "faults/fault_matrix.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <string>

namespace cellctl::faults {
namespace {

const config::CellConfig& cell() {
  static const config::CellConfig c = matrix_cell();
  return c;
}

}  // namespace

void PrintTo(const MatrixCase& c, std::ostream* os) {
  *os << name_of(c);
}

namespace {

class FaultMatrix : public ::testing::TestWithParam<MatrixCase> {};

TEST_P(FaultMatrix, EndsSafeWithinItsBounds) {
  const MatrixCase c = GetParam();
  const auto work =
      std::filesystem::temp_directory_path() / ("cellctl-fault-matrix-" + std::to_string(::getpid()));
  const Expectation e = expectation(c, cell());
  const Outcome o = run_case(c, cell(), work);
  std::filesystem::remove_all(work);
  std::cout << "  [" << fault_spec_text(c, cell()) << " while " << to_string(c.activity)
            << "] detected after " << (o.detected_ms ? std::to_string(*o.detected_ms) : "-") << " ms (bound "
            << e.detect_ms << "), plant at rest after " << (o.safe_ms ? std::to_string(*o.safe_ms) : "never")
            << " ms (bound " << e.safe_ms << "), ended after " << o.ended_ms << " ms: " << o.outcome << "; "
            << o.first_fault << "\n";
  for (const auto& problem : verdict(c, e, o)) ADD_FAILURE() << name_of(c) << ": " << problem;
}

std::string test_name(const ::testing::TestParamInfo<MatrixCase>& info) {
  std::string n = name_of(info.param);
  for (auto& ch : n)
    if (ch == '/' || ch == '=') ch = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(EveryCase, FaultMatrix, ::testing::ValuesIn(all_cases()), test_name);

}  // namespace
}  // namespace cellctl::faults
