// The sanitizer stage's negative twin (scripts/run_sanitized_tests.sh): a
// program with a deliberate heap-buffer-overflow (`heap`) or signed integer
// overflow (`overflow`). The stage requires each to fail with the
// sanitizer's report, so a stage that passes is one that could have failed.
#include <climits>
#include <cstring>

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "heap") == 0) {
    int* values = new int[4]();
    const int read = values[argc + 2];  // values[4]: one past the end
    delete[] values;
    return read;
  }
  if (argc > 1 && std::strcmp(argv[1], "overflow") == 0) {
    volatile int large = INT_MAX - 1;
    const int sum = large + argc;  // INT_MAX - 1 + 2
    volatile int sink = sum;
    return sink == 0;
  }
  return 2;
}
