# pybind11 for the interpreter the top CMakeLists.txt chose (Python3_EXECUTABLE): Debian's
# python3-pybind11 and python3-dev.
set(PYBIND11_FINDPYTHON ON)
find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module)
find_package(pybind11 2.10 REQUIRED CONFIG HINTS /usr/lib/cmake/pybind11)
# The static libraries linked into the module are compiled position-independent (-fPIC,
# glint_library in GlintTargets.cmake). An LTO link of the command still generates its code as a
# PIE executable's, thread-local variables included, so the command is not slowed; without
# -fPIC, LTO left thread_local variables in the executable's TLS model, which a shared object
# cannot hold.
