#include "geodual/pipeline/version.hpp"

#include <iostream>

int main() {
  std::cout << "geodual " << geodual::version() << "\n";
  return 0;
}
