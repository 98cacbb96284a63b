// The main() of every test program: doctest's, plus one guard. CTest runs
// each test case by name (--test-case=NAME); a filter that matches nothing
// would pass without checking anything (CTest cuts names at ';', so a test
// case named "a; b" was run as "a" and never ran). Such a run fails here.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>
#include <cstring>

namespace {

int g_test_cases_run = 0;

// Counts the test cases that start.
struct CountingListener : doctest::IReporter {
  explicit CountingListener(const doctest::ContextOptions&) {}
  void report_query(const doctest::QueryData&) override {}
  void test_run_start() override {}
  void test_run_end(const doctest::TestRunStats&) override {}
  void test_case_start(const doctest::TestCaseData&) override { ++g_test_cases_run; }
  void test_case_reenter(const doctest::TestCaseData&) override {}
  void test_case_end(const doctest::CurrentTestCaseStats&) override {}
  void test_case_exception(const doctest::TestCaseException&) override {}
  void subcase_start(const doctest::SubcaseSignature&) override {}
  void subcase_end() override {}
  void log_assert(const doctest::AssertData&) override {}
  void log_message(const doctest::MessageData&) override {}
  void test_case_skipped(const doctest::TestCaseData&) override {}
};

}  // namespace

REGISTER_LISTENER("xshell_counting", 1, CountingListener);

int main(int argc, char** argv) {
  doctest::Context context(argc, argv);
  const int status = context.run();
  if (context.shouldExit() || status != 0) return status;  // --list-test-cases, --help, failures
  const char* filter = nullptr;
  for (int i = 1; i < argc; ++i)
    for (const char* option : {"--test-case=", "-tc="})
      if (std::strncmp(argv[i], option, std::strlen(option)) == 0)
        filter = argv[i] + std::strlen(option);
  if (filter != nullptr && g_test_cases_run == 0) {
    std::fprintf(
        stderr,
        "test_main: no test case matches \"%s\": nothing was checked (a test case name with ';'? "
        "CTest cuts names there)\n",
        filter);
    return 1;
  }
  return status;
}
