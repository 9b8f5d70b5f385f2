// contactqp.InputError: the library's InputError as a Python exception, a subclass of
// ValueError, with the offending field as its `field` attribute.
#include "contactqp/errors.hpp"
#include "bindings.hpp"

namespace contactqp::python {

void bind_errors(py::module_& m) {
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  input_error.doc() =
      "Bad input: a wrong shape, a non-finite entry, an option out of range, an unknown backend.\n\n"
      "A subclass of ValueError. str(error) is one line, 'field = value: rule', and error.field\n"
      "names the argument or scene key, e.g. 'tol' or 'material.nu'.";
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const InputError& error) {
      py::object type = py::reinterpret_borrow<py::object>(input_error.ptr());
      py::object instance = type(error.what());
      instance.attr("field") = error.field();
      PyErr_SetObject(input_error.ptr(), instance.ptr());
    }
  });
}

}  // namespace contactqp::python
