// The FMU links libstdc++ statically (it must run where no matching libstdc++ is installed),
// so it carries its own copy of the runtime's emergency exception-handling pool, allocated at
// load time. libstdc++ frees it only on request: do so when the importer unloads the FMU
// (freeing the instance → dlclose in fmpy), or every load/unload cycle loses 72,704 bytes
// (valgrind, python_tests/test_valgrind.py). Nothing of this copy runs after the unload.
namespace __gnu_cxx {
void __freeres() noexcept;
}

namespace {
__attribute__((destructor)) void releaseRuntimeAtUnload() { __gnu_cxx::__freeres(); }
}  // namespace
