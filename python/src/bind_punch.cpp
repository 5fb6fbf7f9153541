// python/src/bind_punch.cpp: the types of the punch layer that Python results hold:
//   _rhabel._PressureField: a contact's solved pressure as a function (punch::pressure_field),
//     called with a C-contiguous array of abscissae; the Record of the contact
//     (rhabel._record.Contact) keeps it and calls it from pressure_at(x).
#include "bindings.hpp"

#include <rhabel/punch/contact.hpp>

#include <algorithm>
#include <vector>

namespace rhabel::python {

void bind_punch(py::module_& m) {
  py::class_<punch::pressure_field>(m, "_PressureField")
      .def(
          "__call__",
          [](const punch::pressure_field& field, const double_array& x) {
            const std::vector<double> xs(x.data(), x.data() + x.size());
            std::vector<double> p;
            {
              py::gil_scoped_release nogil;
              p = field(xs);  // std::invalid_argument (a non-finite x): ValueError
            }
            double_array out(std::vector<py::ssize_t>(x.shape(), x.shape() + x.ndim()));
            std::copy(p.begin(), p.end(), out.mutable_data());
            return out;
          },
          py::arg("x"), "p(x) [Pa] at every x (punch::pressure_field).");
}

}  // namespace rhabel::python
