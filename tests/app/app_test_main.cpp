// main() of the app test executables (one ctest per executable): gtest's, except that an executable in which any
// case was skipped (GTEST_SKIP: no shared glTF models, no file-size limit) and none failed exits with 77, so that
// ctest reports it as skipped (SKIP_RETURN_CODE) rather than passed, and scripts/test.sh names it in its summary.
#include <cstdio>

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  const int status = RUN_ALL_TESTS();
  const testing::UnitTest& run = *testing::UnitTest::GetInstance();
  if (status != 0 || run.skipped_test_count() == 0) return status;
  std::printf("%d of %d cases skipped (the others passed): exit 77, reported to ctest as skipped\n",
              run.skipped_test_count(), run.test_to_run_count());
  return 77;
}
