// ctest fixture: writes the synthetic launch table the C tests (capi_c99, c_api_example) read.
#include <exception>
#include <iostream>

#include "tests/predict/synthetic_table.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_test_table OUTPUT.sqlite\n";
    return 2;
  }
  try {
    spread::testing::write_synthetic_table(argv[1]);
  } catch (const std::exception& e) {
    std::cerr << "make_test_table: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
