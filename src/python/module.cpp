// fhr for Python (beyond the paper) — the `fhr._fhr` extension under the `fhr` package
// (src/python/fhr/__init__.py), by topic (bindings.hpp): meshes as numpy arrays in libigl's
// convention (V: n × 3 float64, F: m × 3 integers), validated exactly as the readers validate
// files (spec/mesh.md), and the library's calls on them (spec/library.md): the generator, §2's decimation, §3's exact geodesics,
// the whole method (pipeline::run) and the independent oracle. Errors keep the library's
// taxonomy: the `fhr` package defines the Python classes (InvalidInput is a ValueError) and the
// translator below raises them with the library's one-line messages. Long calls release the GIL.
#include "bindings.hpp"

#include <exception>
#include <string>

#include <fhr/core/errors.hpp>
#include <fhr/version.hpp>

namespace fhr::python {
namespace {

void translate(std::exception_ptr error) {
    // The Python classes live in the pure-Python part of the package (fhr/__init__.py).
    auto raise = [](const char* name, const std::exception& e) {
        const py::object cls = py::module_::import("fhr").attr(name);
        PyErr_SetString(cls.ptr(), e.what());
    };
    try {
        if (error) std::rethrow_exception(error);
    } catch (const InvalidInput& e) {
        raise("InvalidInput", e);
    } catch (const PartitionFailure& e) {
        raise("PartitionFailure", e);
    } catch (const NumericalFailure& e) {
        raise("NumericalFailure", e);
    } catch (const InternalError& e) {
        raise("InternalError", e);
    }
}

}  // namespace
}  // namespace fhr::python

PYBIND11_MODULE(_fhr, m) {
    using namespace fhr::python;
    m.doc() = "fhr's C++ library for Python (see the fhr package).";
    m.attr("__version__") = std::string(fhr::version);
    py::register_exception_translator(&translate);
    bind_meshes(m);
    bind_run(m);
    bind_oracle(m);
}
