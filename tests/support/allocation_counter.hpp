#pragma once
// Counts every call of the global operator new in a test binary that links the counter
// (tests/support/allocation_counter.cpp replaces it with a counting one that only counts), so a
// test can assert that a path allocates nothing: read the count before and after.
namespace vdrive::test {

long allocation_count();

}  // namespace vdrive::test
