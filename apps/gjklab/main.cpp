#include <iostream>

#include "gjklab/cli.hpp"

int main(int argc, char** argv) {
  return gjklab::cli::run(argc, argv, std::cin, std::cout, std::cerr);
}
