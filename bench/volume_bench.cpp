// Placeholder: replaced by the module author.
#include <benchmark/benchmark.h>
BENCHMARK_MAIN();
