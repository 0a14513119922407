// main() of the assembly tests: GoogleTest between PetscInitialize and PetscFinalize.
#include <gtest/gtest.h>
#include <petscsys.h>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (PetscInitialize(nullptr, nullptr, nullptr, nullptr) != 0) return 1;
  const int result = RUN_ALL_TESTS();
  PetscFinalize();
  return result;
}
