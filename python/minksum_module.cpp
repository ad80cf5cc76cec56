// minksum for Python: the extension module minksum._minksum (pybind11).
//
// The package minksum (python/minksum/__init__.py) re-exports what is defined
// here; python/minksum/_minksum.pyi declares it for type checkers.  Only the
// library's public headers are used.
//
// Exact numbers cross the boundary as Python ints and fractions.Fraction,
// converted through GMP's integers (machine words when they fit, else
// hexadecimal text), never through doubles; inputs that cannot be taken
// exactly (complex numbers, numpy long doubles) are refused (to_rational).
// Every computation runs with the GIL released.  Library errors become Python exceptions: InputError
// (bad data: file, place, problem), NotConvexError (an InputError), and
// ValueError for bad requests (UsageError).
#include <minksum/error.hpp>
#include <minksum/io.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/nonconvex.hpp>
#include <minksum/operand.hpp>
#include <minksum/parallel.hpp>
#include <minksum/polytope.hpp>
#include <minksum/proximity.hpp>
#include <minksum/rigid_proximity.hpp>
#include <minksum/solid_io.hpp>
#include <minksum/sum.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <functional>
#include <memory>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <unordered_map>
#include <utility>
#include <variant>
#include <vector>

namespace py = pybind11;
using namespace minksum;

namespace {

using PolytopePtr = std::shared_ptr<const ConvexPolytope>;

// ---------------------------------------------------------------------------
// Numbers.

// Interned for the module's lifetime (never destroyed: the interpreter may be
// gone when static destructors run).
py::object& fraction_type() {
  static auto* t = new py::object(py::module_::import("fractions").attr("Fraction"));
  return *t;
}

py::int_ to_int(const Integer& z) {
  if (mpz_fits_slong_p(z.get_mpz_t())) return py::reinterpret_steal<py::int_>(PyLong_FromLong(mpz_get_si(z.get_mpz_t())));
  std::string text(mpz_sizeinbase(z.get_mpz_t(), 16) + 2, '\0');
  mpz_get_str(text.data(), 16, z.get_mpz_t());
  PyObject* r = PyLong_FromString(text.c_str(), nullptr, 16);
  if (!r) throw py::error_already_set();
  return py::reinterpret_steal<py::int_>(r);
}

py::object to_fraction(const Rational& q) {
  return fraction_type()(to_int(q.get_num()), to_int(q.get_den()));
}

py::tuple to_fractions(const Point3& p) { return py::make_tuple(to_fraction(p.x), to_fraction(p.y), to_fraction(p.z)); }

Integer from_int(py::handle h) {
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(h.ptr(), &overflow);
  if (v == -1 && PyErr_Occurred()) throw py::error_already_set();
  if (!overflow) {
    Integer z;
    mpz_set_si(z.get_mpz_t(), static_cast<long>(v));
    return z;
  }
  py::str hex = py::reinterpret_steal<py::str>(PyNumber_ToBase(h.ptr(), 16));
  if (!hex) throw py::error_already_set();
  std::string s = hex;  // "0x1f" or "-0x1f"
  const bool negative = s[0] == '-';
  Integer z(s.substr(negative ? 3 : 2), 16);
  return negative ? Integer(-z) : z;
}

py::object& numpy_generic() {
  static auto* t = new py::object(py::module_::import("numpy").attr("generic"));
  return *t;
}

py::object& decimal_type() {
  static auto* t = new py::object(py::module_::import("decimal").attr("Decimal"));
  return *t;
}

// "int", "numpy.float128", "decimal.Decimal": the type of h, for messages.
std::string type_name(py::handle h) {
  py::handle t = py::type::handle_of(h);
  const std::string module = py::str(t.attr("__module__")), name = py::str(t.attr("__qualname__"));
  return module == "builtins" ? name : module + "." + name;
}

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

std::string item(const std::string& name, std::size_t i) { return name + "[" + std::to_string(i) + "]"; }

// Refuses the numpy dtypes whose values are not exact coordinates: complex
// numbers, long doubles (more precise than a double: rounding them to
// doubles would not be exact) and what is not a number.  `what` names the
// argument and the position; `array`: the dtype of an array (else a scalar's).
void check_dtype(const py::dtype& dt, const std::string& what, bool array) {
  const char kind = dt.kind();
  const std::string dtype = py::str(static_cast<py::handle>(dt));
  const std::string of = array ? "an array of dtype " + dtype : "numpy." + dtype;
  if (kind == 'c')
    throw py::type_error(what + ": complex numbers are refused (coordinates are real), got " + of);
  if (kind == 'f' && dt.itemsize() > 8)
    throw py::type_error(what + ": numpy.longdouble is refused (its values are not doubles and would be rounded), " +
                         "got " + of + "; convert to float64, or to Fraction(*x.as_integer_ratio()) for the exact values");
  if (std::string("biufOU").find(kind) == std::string::npos)
    throw py::type_error(what + (array ? ": expected numbers, got " : ": expected a number, got ") + of);
}

Rational from_double(double d, const std::string& what) {
  if (!std::isfinite(d)) throw py::value_error(what + ": " + (std::isnan(d) ? "NaN" : "infinite"));
  return Rational(d);
}

// An exact coordinate from a Python number: int, float (the exact value of
// the double), fractions.Fraction (any numbers.Rational), decimal.Decimal
// (its exact value), numpy integer, bool and float scalars of at most 64
// bits, any other number with an exact as_integer_ratio(), or text such as
// "1/3" (parse_number).  Complex numbers and numpy long doubles are refused
// with TypeError: nothing is rounded.  `what` names the argument and the
// position ("vertices[3][2]").
Rational to_rational(py::handle h, const std::string& what) {
  PyObject* o = h.ptr();
  if (PyLong_Check(o)) return Rational(from_int(h));  // and bool
  if (PyFloat_Check(o)) return from_double(PyFloat_AS_DOUBLE(o), what);  // and numpy.float64
  if (PyUnicode_Check(o)) {
    const std::string text = py::cast<std::string>(h);
    std::string why;
    if (auto q = parse_number(text, &why)) return *q;
    throw py::value_error(what + ": '" + text + "': " + why);
  }
  if (PyComplex_Check(o))  // and numpy.complex128
    throw py::type_error(what + ": complex numbers are refused (coordinates are real), got " + type_name(h));
  if (py::isinstance<py::array>(h)) {
    auto a = py::reinterpret_borrow<py::array>(h);
    if (a.ndim() != 0) throw py::type_error(what + ": expected a number, got an array of shape " + shape_text(a));
    check_dtype(a.dtype(), what, true);
    return to_rational(a.attr("item")(), what);
  }
  if (py::isinstance(h, numpy_generic())) {
    const py::dtype dt = h.attr("dtype");
    check_dtype(dt, what, false);
    switch (dt.kind()) {
      case 'b': return Rational(PyObject_IsTrue(o) ? 1 : 0);
      case 'f':  // float16, float32: exact as doubles
        return from_double(py::cast<double>(py::float_(py::reinterpret_borrow<py::object>(h))), what);
      default: break;  // integers: below
    }
  }
  if (py::isinstance(h, decimal_type())) {
    if (!py::cast<bool>(h.attr("is_finite")()))
      throw py::value_error(what + ": " + std::string(py::repr(h)) + " is not a finite number");
    const py::tuple r = h.attr("as_integer_ratio")();
    Rational q(from_int(r[0]), from_int(r[1]));
    q.canonicalize();
    return q;
  }
  if (PyIndex_Check(o)) {
    py::object i = py::reinterpret_steal<py::object>(PyNumber_Index(o));
    if (!i) throw py::error_already_set();
    return Rational(from_int(i));
  }
  if (py::hasattr(h, "numerator") && py::hasattr(h, "denominator")) {  // numbers.Rational
    Rational q(from_int(py::int_(h.attr("numerator"))), from_int(py::int_(h.attr("denominator"))));
    if (q.get_den() == 0) throw py::value_error(what + ": zero denominator");
    q.canonicalize();
    return q;
  }
  if (py::hasattr(h, "as_integer_ratio")) {  // an exact binary or decimal float of another library
    py::tuple r;
    try {
      r = h.attr("as_integer_ratio")();
    } catch (py::error_already_set& e) {
      if (!e.matches(PyExc_ValueError) && !e.matches(PyExc_OverflowError)) throw;
      throw py::value_error(what + ": " + std::string(py::repr(h)) + " is not a finite number");
    }
    Rational q(from_int(py::int_(r[0])), from_int(py::int_(r[1])));
    if (q.get_den() == 0) throw py::value_error(what + ": zero denominator");
    q.canonicalize();
    return q;
  }
  throw py::type_error(what + ": expected a number (int, float, Fraction, Decimal or text such as '1/3'), got " +
                       type_name(h));
}

bool is_text(py::handle h) { return PyUnicode_Check(h.ptr()) || PyBytes_Check(h.ptr()) || PyByteArray_Check(h.ptr()); }

// A sequence (list, tuple, array...) that is not text.
bool is_sequence(py::handle h) {
  if (py::isinstance<py::array>(h)) return py::reinterpret_borrow<py::array>(h).ndim() > 0;
  return !is_text(h) && PySequence_Check(h.ptr());
}

// One point: a triple (x, y, z) of exact numbers, or a numpy array of shape (3,).
Point3 to_triple(py::handle h, const std::string& where) {
  if (py::isinstance<py::array>(h)) {
    auto a = py::reinterpret_borrow<py::array>(h);
    check_dtype(a.dtype(), where, true);
    if (a.ndim() != 1 || a.shape(0) != 3)
      throw py::value_error(where + ": expected a triple (x, y, z), got an array of shape " + shape_text(a));
  } else if (!is_sequence(h)) {
    throw py::type_error(where + ": expected a triple (x, y, z), got " + type_name(h));
  }
  const auto r = py::reinterpret_borrow<py::sequence>(h);
  const std::size_t n = r.size();
  if (n != 3) throw py::value_error(where + ": expected a triple (x, y, z), got " + std::to_string(n) + " items");
  Rational c[3];  // in order: the first bad coordinate is the one reported
  for (std::size_t k = 0; k < 3; ++k) c[k] = to_rational(r[k], item(where, k));
  return Point3(std::move(c[0]), std::move(c[1]), std::move(c[2]));
}

// Points from an (n, 3) array (float arrays of at most 64 bits: each double
// taken exactly; integer, bool, object and text arrays: each entry as
// to_rational takes it) or a sequence of triples.
PointList to_points(py::handle h, const std::string& name) {
  PointList pts;
  if (py::isinstance<py::array>(h)) {
    auto arr = py::reinterpret_borrow<py::array>(h);
    check_dtype(arr.dtype(), name, true);
    if (arr.ndim() != 2 || arr.shape(1) != 3)
      throw py::value_error(name + ": expected an (n, 3) array, got an array of shape " + shape_text(arr));
    if (arr.dtype().kind() == 'f') {
      auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
      if (!a) throw py::error_already_set();
      auto r = a.unchecked<2>();
      pts.reserve(static_cast<std::size_t>(r.shape(0)));
      for (py::ssize_t i = 0; i < r.shape(0); ++i) {
        const Vec3d v{r(i, 0), r(i, 1), r(i, 2)};
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
          throw py::value_error(item(name, static_cast<std::size_t>(i)) + ": not finite");
        pts.push_back(v);
      }
      return pts;
    }
  } else if (!is_sequence(h)) {
    throw py::type_error(name + ": expected an (n, 3) array or a sequence of (x, y, z) triples, got " + type_name(h));
  }
  auto seq = py::reinterpret_borrow<py::sequence>(h);
  const std::size_t n = seq.size();
  pts.reserve(n);
  for (std::size_t i = 0; i < n; ++i) pts.push_back(to_triple(seq[i], item(name, i)));
  return pts;
}

// Whether h is a batch of points: an array of two dimensions, or a non-empty
// sequence whose first item is a sequence.
bool is_batch(py::handle h) {
  if (py::isinstance<py::array>(h)) return py::reinterpret_borrow<py::array>(h).ndim() == 2;
  if (is_sequence(h) && py::len(h) > 0) return is_sequence(py::reinterpret_borrow<py::sequence>(h)[0]);
  return false;
}

// One translation or direction (`what`): a triple, or an array of shape (3,).
// A batch (an (N, 3) array, a sequence of triples) is refused with ValueError.
Point3 to_point(py::handle h, const std::string& name, const char* what = "translation") {
  bool batch = false;
  if (py::isinstance<py::array>(h)) {
    auto a = py::reinterpret_borrow<py::array>(h);
    batch = a.ndim() == 2 && a.shape(1) == 3;
  } else if (is_sequence(h) && py::len(h) > 0) {
    py::object first = py::reinterpret_borrow<py::sequence>(h)[0];
    batch = is_sequence(first);
  }
  if (batch) {
    const std::string given = py::isinstance<py::array>(h)
                                  ? "an array of shape " + shape_text(py::reinterpret_borrow<py::array>(h))
                                  : std::string("a sequence of triples");
    throw py::value_error(name + ": takes one " + what + ", a triple (x, y, z), not a batch of them (" + given +
                          "): query each " + what + " on its own");
  }
  return to_triple(h, name);
}

// ---------------------------------------------------------------------------
// Errors.

py::object& errors_module() {
  static auto* m = new py::object(py::module_::import("minksum._errors"));
  return *m;
}

void raise_input_error(const char* type_name, const InputError& e) {
  py::object type = errors_module().attr(type_name);
  py::object value = type(e.file(), e.place(), e.problem());
  PyErr_SetObject(type.ptr(), value.ptr());
}

// The Python exception for a C++ one, as an object (for on_error="return").
py::object exception_object(std::exception_ptr p) {
  try {
    std::rethrow_exception(p);
  } catch (const NotConvexError& e) {
    return errors_module().attr("NotConvexError")(e.file(), e.place(), e.problem());
  } catch (const InputError& e) {
    return errors_module().attr("InputError")(e.file(), e.place(), e.problem());
  } catch (const UsageError& e) {
    return py::reinterpret_borrow<py::object>(PyExc_ValueError)(e.what());
  } catch (const std::bad_alloc&) {
    return py::reinterpret_borrow<py::object>(PyExc_MemoryError)();
  } catch (const std::exception& e) {
    return py::reinterpret_borrow<py::object>(PyExc_RuntimeError)(e.what());
  }
}

// ---------------------------------------------------------------------------
// Operands and methods.

Method to_method(const std::string& name) {
  auto m = parse_method(name);
  if (!m) throw py::value_error("unknown method '" + name + "' (" + method_list() + ")");
  if (!method_available(*m)) throw py::value_error("method '" + name + "' is not implemented in this build");
  return *m;
}

// A polytope, or a name to load (a file path or catalog spec) later, with the GIL released.
using NamedOperand = std::variant<PolytopePtr, std::string>;

NamedOperand to_operand(py::handle h, const char* name) {
  if (py::isinstance<ConvexPolytope>(h)) return PolytopePtr(py::cast<std::shared_ptr<ConvexPolytope>>(h));
  if (py::isinstance<py::str>(h)) return py::cast<std::string>(h);
  if (PyObject_HasAttrString(h.ptr(), "__fspath__"))  // os.PathLike
    return py::cast<std::string>(py::module_::import("os").attr("fsdecode")(h));
  throw py::type_error(std::string(name) + ": expected a Polytope, a file path or a catalog name, got " + type_name(h));
}

PolytopePtr resolve(const NamedOperand& o, bool hull = false) {
  if (auto* p = std::get_if<PolytopePtr>(&o)) return *p;
  return std::make_shared<const ConvexPolytope>(load_polytope(std::get<std::string>(o), hull));
}

// ---------------------------------------------------------------------------
// The result of a sum: the polytope (the base class, so a Sum is a Polytope
// in Python), how it was computed, and where its vertices and facets come from.
struct Sum : ConvexPolytope {
  Method method = Method::automatic;
  std::vector<std::pair<Index, Index>> vertex_origin;
  std::vector<FacetProvenance> provenance;  // computed on first use when the method does not record it
  std::vector<std::pair<std::string, long long>> counters;
  double seconds = 0;
  const char* route = nullptr;  // a sum with a point, segment or polygon: how it was made
  PolytopePtr a, b;  // the operands, until the provenance is known
  std::mutex provenance_mutex;

  Sum() = default;
  Sum(SumResult&& r, PolytopePtr a_, PolytopePtr b_)
      : ConvexPolytope(std::move(r.polytope)), method(r.method), vertex_origin(std::move(r.vertex_origin)),
        provenance(std::move(r.facet_provenance)), counters(std::move(r.counters)), seconds(r.seconds) {
    if (provenance.empty()) a = std::move(a_), b = std::move(b_);
  }

  const std::vector<FacetProvenance>& facet_provenance_list() {
    std::lock_guard<std::mutex> lock(provenance_mutex);
    if (provenance.empty() && num_facets() > 0 && a) {
      provenance = facet_provenance(*a, *b, *this);
      a.reset();
      b.reset();
    }
    return provenance;
  }
};

// Ctrl-C during a long sum: the progress callback (run at the method's report
// points, on the thread computing) checks for signals with the GIL held.
struct Interrupted {};

// Runs work() on a thread of its own while the calling thread, the GIL
// released, waits for it, checking for signals with the GIL held every 50 ms
// (Python runs signal handlers on the main thread only, and a batch's jobs
// run on other threads).  When a handler raises (Ctrl-C: KeyboardInterrupt),
// *cancel is set, work() is waited for (the sums stop at their next report
// point, SumOptions::cancel, and no new job starts) and the handler's
// exception is raised.  An exception of work() is rethrown.
void run_interruptible(const std::function<void()>& work, std::atomic<bool>& cancel) {
  std::mutex mu;
  std::condition_variable cv;
  bool done = false;
  std::exception_ptr failure;
  PyObject *type = nullptr, *value = nullptr, *traceback = nullptr;  // the handler's exception
  {
    py::gil_scoped_release nogil;
    std::thread runner([&] {
      try {
        work();
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mu);
      done = true;
      cv.notify_all();
    });
    std::unique_lock<std::mutex> lock(mu);
    while (!cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) {
      if (type) continue;  // interrupted: waiting for the jobs under way to stop
      lock.unlock();
      {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) {
          PyErr_Fetch(&type, &value, &traceback);
          cancel = true;
        }
      }
      lock.lock();
    }
    lock.unlock();
    runner.join();
  }
  if (type) {
    PyErr_Restore(type, value, traceback);
    throw py::error_already_set();
  }
  if (failure) std::rethrow_exception(failure);
}

// ---------------------------------------------------------------------------
// Conversions to Python.

const char* feature_kind(FeatureDim d) {
  return d == FeatureDim::vertex ? "vertex" : d == FeatureDim::edge ? "edge" : "facet";
}
py::tuple feature(const Feature& f) { return py::make_tuple(feature_kind(f.dim), f.index); }

py::array_t<std::int64_t> index_array(const std::vector<Index>& v) {
  py::array_t<std::int64_t> a(static_cast<py::ssize_t>(v.size()));
  auto r = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < v.size(); ++i) r(static_cast<py::ssize_t>(i)) = v[i];
  return a;
}

// The nearest doubles of the coordinates, as a read-only (n, 3) view of the
// polytope's own storage (no copy); `owner` keeps the polytope alive.
py::array vertices_view(const ConvexPolytope& p, py::handle owner) {
  static_assert(sizeof(Vec3d) == 3 * sizeof(double), "Vec3d is three packed doubles");
  const auto& approx = p.coordinates().approx();
  py::array_t<double> a({static_cast<py::ssize_t>(approx.size()), py::ssize_t{3}},
                        {static_cast<py::ssize_t>(sizeof(Vec3d)), static_cast<py::ssize_t>(sizeof(double))},
                        approx.empty() ? nullptr : &approx[0].x, owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

// The faces' loops (sequences of vertex indices, an (m, k) integer array)
// into mesh.faces, each index checked against mesh.points.
void read_faces(Mesh& mesh, py::handle faces) {
  if (!is_sequence(faces))
    throw py::type_error("faces: expected a sequence of index sequences, got " + type_name(faces));
  const std::size_t n = mesh.points.size();
  for (py::handle f : faces) {
    const std::string where = item("faces", mesh.faces.size());
    if (!is_sequence(f)) throw py::type_error(where + ": expected a sequence of vertex indices, got " + type_name(f));
    std::vector<Index> loop;
    for (py::handle i : f) {
      if (!PyIndex_Check(i.ptr()))
        throw py::type_error(where + ": expected integer vertex indices, got " + type_name(i));
      py::object v = py::reinterpret_steal<py::object>(PyNumber_Index(i.ptr()));
      if (!v) throw py::error_already_set();
      int overflow = 0;
      const long long x = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
      if (x == -1 && PyErr_Occurred()) throw py::error_already_set();
      if (overflow || x < 0 || static_cast<unsigned long long>(x) >= n)
        throw py::value_error(where + ": " + std::string(py::str(v)) + " is not a vertex index (0.." +
                              std::to_string(n ? n - 1 : 0) + ")");
      loop.push_back(static_cast<Index>(x));
    }
    mesh.faces.push_back(std::move(loop));
  }
}

ConvexPolytope polytope_from(PointList points, py::handle faces) {
  Mesh mesh;
  mesh.points = std::move(points);
  if (faces.is_none()) {
    py::gil_scoped_release nogil;
    return ConvexPolytope::hull(mesh.points);
  }
  read_faces(mesh, faces);
  py::gil_scoped_release nogil;
  return ConvexPolytope::from_mesh(mesh);
}

ConvexPolytope polytope_from(py::handle vertices, py::handle faces, const char* name = "vertices") {
  return polytope_from(to_points(vertices, name), faces);
}

// ---------------------------------------------------------------------------
// Solids (<minksum/nonconvex.hpp>).

// A closed polyhedral solid, convex or not: its faces as polygons (the input's
// faces after welding, or a non-convex sum's boundary), its exact volume, and
// the validated Solid that sums take (for a sum's result, validated on first
// use as an operand: its boundary may touch itself, which validate_solid
// refuses).
struct SolidPy {
  Mesh faces;
  Rational volume;
  std::optional<Solid> solid;
  std::string name;  // the source named in errors ("" for arrays)
  // The boundary as a convex polytope when the operation built one (the
  // erosion, opening or closing of a convex a): save writes it as a
  // polytope is written, as 'minksum erode|open|close -o' does.
  std::shared_ptr<const ConvexPolytope> convex_written;
  mutable std::mutex solid_mutex;  // guards `solid` (set by validated() on another thread)

  const Solid& validated() {
    std::lock_guard<std::mutex> lock(solid_mutex);
    if (!solid) solid = validate_solid(faces, name);
    return *solid;
  }
  // Whether the solid is exactly a convex polytope (a sum's boundary that
  // does not validate as a solid, touching itself, is not).
  bool is_convex() {
    try {
      return validated().convex.has_value();
    } catch (const InputError&) {
      return false;
    }
  }
  // The surface as triangles: the validated solid's, else the faces cut by ear clipping.
  Mesh triangles() const {
    {
      std::lock_guard<std::mutex> lock(solid_mutex);
      if (solid) return solid->triangles;
    }
    return triangulate(faces, name);
  }
};
using SolidPtr = std::shared_ptr<SolidPy>;

SolidPtr solid_from(Solid s, std::string name) {
  auto out = std::make_shared<SolidPy>();
  out->faces = solid_faces(s);
  out->volume = s.volume;
  out->name = std::move(name);
  out->solid = std::move(s);
  return out;
}

// The result of a non-convex sum: the boundary as a SolidPy, and the report
// the command prints (NonconvexSum without its mesh).
struct SolidSum : SolidPy {
  NonconvexSum report;
};

// A point, a segment or a flat convex polygon (a convex set of dimension
// below 3, docs/sweeps.md), or the result of a sum that is one.
struct SetPy {
  ConvexSet set;
  std::string name;           // the source named in errors ("" for arrays)
  const char* method = nullptr;  // a sum's: its method and route (else null)
  const char* route = nullptr;
  double seconds = 0;
};
using SetPtr = std::shared_ptr<const SetPy>;

// An operand of minkowski_sum: a Solid, a Polytope, a ConvexSet, or a name
// loaded later (Operand::load, <minksum/sum.hpp>) with the GIL released.
using AnyOperandPy = std::variant<SolidPtr, PolytopePtr, std::string, SetPtr>;

AnyOperandPy to_any_operand(py::handle h, const char* name) {
  if (py::isinstance<SolidPy>(h)) return py::cast<SolidPtr>(h);
  if (py::isinstance<SetPy>(h)) return SetPtr(py::cast<std::shared_ptr<SetPy>>(h));
  if (!py::isinstance<ConvexPolytope>(h) && !py::isinstance<py::str>(h) &&
      !PyObject_HasAttrString(h.ptr(), "__fspath__"))
    throw py::type_error(std::string(name) + ": expected a Polytope, a Solid, a ConvexSet, a file path or a catalog "
                                             "name, got " + type_name(h));
  NamedOperand o = to_operand(h, name);
  if (auto* p = std::get_if<PolytopePtr>(&o)) return *p;
  return std::get<std::string>(o);
}

// A name as a solid: a convex polytope (file or catalog) as the solid it is,
// else the mesh validated as a closed solid.  What is neither (a point cloud,
// an open surface, a polygon) is refused with load() 's error, so that a name
// that load() refuses is refused here in the same words.
Solid load_solid(const std::string& spec) {
  AnyOperand any = load_any_operand(spec);
  if (any.polytope) return solid_of(*any.polytope);
  if (!any.flat) {
    try {
      return validate_solid(any.mesh, spec);
    } catch (const InputError&) {
      // load_polytope's error (NotConvexError with its hint...) when it has one
      load_polytope(spec);
      throw;
    }
  }
  load_polytope(spec);  // a point, segment or polygon: load()'s refusal
  throw InputError(spec, "", "not a solid");
}

// The library's operand (with the GIL released): a name is read as what it
// is (a convex polytope, a point, segment or polygon, or a closed solid).
Operand library_operand(const AnyOperandPy& o) {
  if (auto* s = std::get_if<SolidPtr>(&o)) return Operand((*s)->validated(), (*s)->name);
  if (auto* p = std::get_if<PolytopePtr>(&o)) return Operand(**p);
  if (auto* c = std::get_if<SetPtr>(&o)) return Operand((*c)->set, (*c)->name);
  const std::string& name = std::get<std::string>(o);
  return Operand::load(name);
}

// What minkowski_sum returns: a Sum (a convex polytope), a SolidSum (the
// boundary of a sum with a solid, an erosion, opening or closing) or a
// ConvexSet (a point, segment or polygon).
using SumPy = std::variant<std::shared_ptr<Sum>, std::shared_ptr<SolidSum>, std::shared_ptr<SetPy>>;

// a ⊕ b (or the operation) of the library's operands by its one sum
// (<minksum/sum.hpp>), with the GIL released; `a` and `b` as given (a
// Polytope is kept for the provenance of a method that does not record it).
// For erode, opening and closing a b that is not a convex polytope is a
// ValueError.
SumPy sum_operands(const AnyOperandPy& a, const AnyOperandPy& b, const std::vector<Operand>& operands, Method method,
                   const SumOptions& options, unsigned threads, SumOperation operation = SumOperation::sum) {
  if (operation != SumOperation::sum && !operands[1].polytope() &&
      !(operands[1].solid() && operands[1].solid()->convex))
    throw std::invalid_argument("b is not a convex polytope: erode, opening and closing take a convex b (a of any "
                                "shape)");
  SumRequest request;
  request.operation = operation;
  request.method = method;
  request.options = options;
  request.threads = threads;
  OperandSum r = minkowski_sum(operands, request);
  if (auto* convex = std::get_if<SumResult>(&r.result)) {
    PolytopePtr pa, pb;
    if (!r.report.route && convex->facet_provenance.empty()) {
      auto kept = [](const AnyOperandPy& o, const Operand& loaded) {
        if (auto* p = std::get_if<PolytopePtr>(&o)) return *p;
        return std::make_shared<const ConvexPolytope>(*loaded.polytope());
      };
      pa = kept(a, operands[0]);
      pb = kept(b, operands[1]);
    }
    auto out = std::make_shared<Sum>(std::move(*convex), pa, pb);
    out->route = r.report.route;
    return out;
  }
  if (auto* set = std::get_if<SetSumResult>(&r.result)) {
    auto out = std::make_shared<SetPy>();
    out->set = std::move(set->set);
    out->method = method_name(set->method);
    out->route = set->route;
    out->seconds = r.report.seconds;
    return out;
  }
  auto out = std::make_shared<SolidSum>();
  out->report = std::move(std::get<NonconvexSum>(r.result));
  out->faces = std::move(out->report.mesh);
  out->report.mesh = Mesh{};
  if (out->report.convex) {
    out->convex_written = std::make_shared<const ConvexPolytope>(std::move(*out->report.convex));
    out->report.convex.reset();
  }
  out->volume = out->report.volume;
  return out;
}

std::vector<Operand> library_operands(const AnyOperandPy& a, const AnyOperandPy& b) {
  std::vector<Operand> operands;
  operands.push_back(library_operand(a));
  operands.push_back(library_operand(b));
  return operands;
}

// sum_operands of two operands as given, names loaded (GIL released).
SumPy sum_any(const AnyOperandPy& a, const AnyOperandPy& b, Method method, const SumOptions& options,
              unsigned threads, SumOperation operation = SumOperation::sum) {
  return sum_operands(a, b, library_operands(a, b), method, options, threads, operation);
}

// One sum from Python, GIL released, Ctrl-C honoured.  Convex sums and
// sweeps run on the calling thread and check for signals at the method's
// report points (KeyboardInterrupt raised inside the sum); a sum with a
// solid runs on its own thread (its report points are on worker threads)
// while this one checks for signals and cancels it (run_interruptible).
py::object sum_interruptible(const AnyOperandPy& a, const AnyOperandPy& b, Method method,
                             SumOperation operation = SumOperation::sum) {
  std::vector<Operand> operands;
  {
    py::gil_scoped_release nogil;
    operands = library_operands(a, b);
  }
  SumPy out;
  if (operation == SumOperation::sum && !operands[0].solid() && !operands[1].solid()) {
    SumOptions options;
    options.progress = [](const char*, double) {
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {
        PyErr_Clear();
        throw Interrupted{};
      }
    };
    py::gil_scoped_release nogil;
    out = sum_operands(a, b, operands, method, options, 0, operation);
  } else {
    std::atomic<bool> cancel{false};
    SumOptions options;
    options.cancel = &cancel;
    run_interruptible([&] { out = sum_operands(a, b, operands, method, options, 0, operation); }, cancel);
  }
  return std::visit([](const auto& r) { return py::cast(r); }, out);
}

// Pickling of solids and convex sets (minksum.dask sends results between
// processes): exact coordinates as text, faces as index lists.
py::list exact_points_state(const PointList& pts) {
  py::list out;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Point3 q = pts.exact(i);
    out.append(py::make_tuple(format_exact(q.x), format_exact(q.y), format_exact(q.z)));
  }
  return out;
}

py::tuple solid_state(const SolidPy& s) {
  py::list faces;
  for (const auto& f : s.faces.faces) faces.append(py::cast(f));
  return py::make_tuple(exact_points_state(s.faces.points), faces, format_exact(s.volume), s.name);
}

// The boundary as it was (a sum's boundary may touch itself: it is not
// validated again until it is used as an operand).
void solid_from_state(SolidPy& s, const py::tuple& t) {
  if (t.size() != 4) throw py::value_error("Solid: bad pickled state");
  s.faces.points = to_points(t[0], "vertices");
  read_faces(s.faces, t[1]);
  s.volume = Rational(py::cast<std::string>(t[2]));
  s.volume.canonicalize();
  s.name = py::cast<std::string>(t[3]);
}

// The literal among `names` equal to `text` (the report's names are string literals).
const char* literal(const std::string& text, std::initializer_list<const char*> names, const char* what) {
  for (const char* n : names)
    if (text == n) return n;
  throw py::value_error(std::string(what) + ": bad pickled state");
}

py::array_t<double> points_array(const PointList& pts) {
  py::array_t<double> a({static_cast<py::ssize_t>(pts.size()), py::ssize_t{3}});
  auto r = a.mutable_unchecked<2>();
  const auto& approx = pts.approx();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    r(static_cast<py::ssize_t>(i), 0) = approx[i].x;
    r(static_cast<py::ssize_t>(i), 1) = approx[i].y;
    r(static_cast<py::ssize_t>(i), 2) = approx[i].z;
  }
  return a;
}

py::array_t<std::int64_t> triangle_array(const Mesh& t) {
  py::array_t<std::int64_t> a({static_cast<py::ssize_t>(t.faces.size()), py::ssize_t{3}});
  auto r = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < t.faces.size(); ++i)
    for (int k = 0; k < 3; ++k) r(static_cast<py::ssize_t>(i), k) = t.faces[i][k];
  return a;
}

py::bytes vec_bytes(const std::vector<Vec3d>& v) {
  return py::bytes(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(Vec3d));
}

std::vector<Vec3d> bytes_vec(py::handle b) {
  const std::string s = py::cast<std::string>(py::reinterpret_borrow<py::bytes>(b));
  if (s.size() % sizeof(Vec3d) != 0) throw py::value_error("Polytope: bad pickled state");
  std::vector<Vec3d> v(s.size() / sizeof(Vec3d));
  std::memcpy(v.data(), s.data(), s.size());
  return v;
}

// Pickling: the facet loops and the coordinates in their own exact form
// (doubles, or the sum hi + lo of two doubles, as bytes; rationals as text),
// so that the copy keeps the form and validates as fast as the original.
py::tuple polytope_state(const ConvexPolytope& p) {
  py::list faces;
  for (Index f = 0; f < p.num_facets(); ++f) faces.append(py::cast(p.facet_vertices(f)));
  const PointList& c = p.coordinates();
  if (p.coordinates_are_doubles()) return py::make_tuple("doubles", vec_bytes(c.approx()), faces);
  if (c.form() == PointList::Form::double_pairs) {
    std::vector<Vec3d> lo(c.size());
    for (std::size_t i = 0; i < c.size(); ++i) lo[i] = c.low(i);
    return py::make_tuple("pairs", py::make_tuple(vec_bytes(c.approx()), vec_bytes(lo)), faces);
  }
  py::list coords;
  for (std::size_t i = 0; i < p.num_vertices(); ++i) {
    const Point3 q = p.coordinates().exact(i);
    coords.append(py::make_tuple(format_exact(q.x), format_exact(q.y), format_exact(q.z)));
  }
  return py::make_tuple("exact", coords, faces);
}

ConvexPolytope polytope_from_state(const py::tuple& t) {
  if (t.size() != 3) throw py::value_error("Polytope: bad pickled state");
  const std::string kind = py::cast<std::string>(t[0]);
  if (kind == "exact") return polytope_from(t[1], t[2]);
  PointList points;
  if (kind == "doubles") {
    for (const Vec3d& v : bytes_vec(t[1])) points.push_back(v);
  } else if (kind == "pairs") {
    const auto parts = py::cast<py::tuple>(t[1]);
    const std::vector<Vec3d> hi = bytes_vec(parts[0]), lo = bytes_vec(parts[1]);
    if (hi.size() != lo.size()) throw py::value_error("Polytope: bad pickled state");
    for (std::size_t i = 0; i < hi.size(); ++i) points.push_pair(hi[i], lo[i]);
  } else {
    throw py::value_error("Polytope: bad pickled state");
  }
  return polytope_from(std::move(points), t[2]);
}

py::list provenance_list(Sum& s) {
  py::list out;
  for (const FacetProvenance& p : s.facet_provenance_list())
    out.append(py::make_tuple(facet_origin_name(p.origin()), feature(p.a), feature(p.b)));
  return out;
}

// ---------------------------------------------------------------------------
// Proximity.

struct Obstacle {
  PolytopePtr p, q;
  Method method = Method::automatic;
  std::unique_ptr<TranslationalObstacle> o;
  // For batches on several threads: more obstacles of the same P and Q (a
  // TranslationalObstacle answers one query at a time), built on first use
  // and kept.
  std::vector<std::unique_ptr<TranslationalObstacle>> workers;
  std::mutex m;  // one query or batch at a time
};

// A batch runs on at most one thread per this many translations.
constexpr std::size_t kPosesPerThread = 64;

// A batch of translations t[i] answered on `threads` threads (None: one per
// hardware thread), each thread a contiguous block of poses on its own
// obstacle; out[i] = answer(t[i]), the answer of the single query.
template <class Result, class Answer>
std::vector<Result> batch(Obstacle& o, const std::vector<Point3>& t, std::optional<long long> threads, Answer answer) {
  if (threads && *threads < 1) throw py::value_error("threads must be at least 1 (or None: one per core)");
  std::vector<Result> out(t.size());
  py::gil_scoped_release nogil;
  std::lock_guard<std::mutex> lock(o.m);
  const std::size_t blocks = (t.size() + kPosesPerThread - 1) / kPosesPerThread;
  const unsigned n = parallel_threads(threads ? static_cast<unsigned>(*threads) : 0u, blocks);
  while (o.workers.size() + 1 < n)
    o.workers.push_back(std::make_unique<TranslationalObstacle>(*o.p, *o.q, o.method));
  parallel_for(n, n, [&](std::size_t k) {
    TranslationalObstacle& ob = k == 0 ? *o.o : *o.workers[k - 1];
    const std::size_t begin = t.size() * k / n, end = t.size() * (k + 1) / n;
    for (std::size_t i = begin; i < end; ++i) out[i] = answer(ob, t[i]);
  });
  return out;
}

std::vector<Point3> to_translations(py::handle h) {
  const PointList pts = to_points(h, "t");
  std::vector<Point3> t;
  t.reserve(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) t.push_back(pts.exact(i));
  return t;
}

// A query of Obstacle on t (the translation of Q relative to P): t converted
// with the GIL held, then answered with it released, one query at a time.
// A batch of translations (an (N, 3) array or a sequence of triples) gives
// the array value(result) of each (exact=True: the list of the results).
template <class Result, class Value>
auto query(Result (TranslationalObstacle::*answer)(const Point3&), Value value) {
  return [answer, value](Obstacle& o, py::object t, bool exact, std::optional<long long> threads) -> py::object {
    if (is_batch(t)) {
      const std::vector<Point3> ts = to_translations(t);
      std::vector<Result> r =
          batch<Result>(o, ts, threads, [answer](TranslationalObstacle& ob, const Point3& s) { return (ob.*answer)(s); });
      if (exact) {
        py::list out;
        for (Result& x : r) out.append(py::cast(std::move(x)));
        return out;
      }
      return value(r);
    }
    const Point3 s = to_point(t, "t");
    Result r;
    {
      py::gil_scoped_release nogil;
      std::lock_guard<std::mutex> lock(o.m);
      r = ((*o.o).*answer)(s);
    }
    return py::cast(std::move(r));
  };
}

template <class Result>
py::array_t<std::int8_t> status_array(const std::vector<Result>& r) {
  py::array_t<std::int8_t> a(static_cast<py::ssize_t>(r.size()));
  auto w = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < r.size(); ++i) w(static_cast<py::ssize_t>(i)) = static_cast<std::int8_t>(r[i].status);
  return a;
}

template <class Result, class F>
py::array_t<double> double_array(const std::vector<Result>& r, F f) {
  py::array_t<double> a(static_cast<py::ssize_t>(r.size()));
  auto w = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < r.size(); ++i) w(static_cast<py::ssize_t>(i)) = f(r[i]);
  return a;
}


// Poses under rigid motion (collide_rigid): translations t, an (N, 3) or (3,)
// array (floats taken exactly, integers exactly) or None (zero), and
// rotations r, an (N, 4) or (4,) integer array of quaternions, an (N, 3, 3)
// or (3, 3) float array of matrices (taken exactly), or None (the
// identity).  One pose of either stands for every pose.
struct PoseInput {
  std::size_t count = 1;  // 1: one pose for all
  PointList t;            // empty: zero
  std::vector<std::array<long long, 4>> quaternions;  // non-zero; made GMP integers by make_pose
  std::vector<std::array<double, 9>> matrices;
};

PoseInput to_pose_input(py::handle t, py::handle r, const std::string& tn, const std::string& rn) {
  PoseInput in;
  std::size_t nt = 1, nr = 1;
  if (!t.is_none()) {
    py::array a = py::array::ensure(t);
    if (!a) throw py::type_error(tn + ": expected an (N, 3) or (3,) array of translations, got " + type_name(t));
    if (a.ndim() == 1) {
      in.t.push_back(to_point(t, tn));
    } else {
      in.t = to_points(t, tn);
      nt = in.t.size();
    }
  }
  if (!r.is_none()) {
    py::array a = py::array::ensure(r);
    if (!a) throw py::type_error(rn + ": expected quaternions (N, 4) or matrices (N, 3, 3), got " + type_name(r));
    check_dtype(a.dtype(), rn, true);
    const char kind = a.dtype().kind();
    const bool quaternions = (a.ndim() == 2 && a.shape(1) == 4) || (a.ndim() == 1 && a.shape(0) == 4);
    const bool matrices = (a.ndim() == 3 && a.shape(1) == 3 && a.shape(2) == 3) || (a.ndim() == 2 && a.shape(0) == 3 && a.shape(1) == 3);
    if (quaternions) {
      if (kind != 'i' && kind != 'u')
        throw py::type_error(rn + ": quaternions must be integers (their rotation is exact); give a rotation of "
                                  "floats as a (3, 3) matrix, got an array of dtype " + std::string(py::str(static_cast<py::handle>(a.dtype()))));
      auto q = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(r);
      const std::size_t n = a.ndim() == 1 ? 1 : static_cast<std::size_t>(a.shape(0));
      const long long* d = q.data();
      in.quaternions.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        std::copy_n(d + 4 * i, 4, in.quaternions[i].begin());
        if (!d[4 * i] && !d[4 * i + 1] && !d[4 * i + 2] && !d[4 * i + 3])
          throw py::value_error(item(rn, i) + ": the zero quaternion is not a rotation");
      }
      if (a.ndim() == 2) nr = n;
    } else if (matrices) {
      if (kind != 'f') throw py::type_error(rn + ": rotation matrices must be floats, got an array of dtype " +
                                            std::string(py::str(static_cast<py::handle>(a.dtype()))));
      auto m = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(r);
      const std::size_t n = a.ndim() == 2 ? 1 : static_cast<std::size_t>(a.shape(0));
      const double* d = m.data();
      in.matrices.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        std::array<double, 9>& x = in.matrices[i];
        for (int k = 0; k < 9; ++k) {
          x[k] = d[9 * i + k];
          if (!std::isfinite(x[k])) throw py::value_error(item(rn, i) + ": not finite");
        }
      }
      if (a.ndim() == 3) nr = n;
    } else {
      throw py::value_error(rn + ": expected quaternions (N, 4) or matrices (N, 3, 3), got an array of shape " +
                            shape_text(a));
    }
  }
  if (nt != 1 && nr != 1 && nt != nr)
    throw py::value_error(tn + " and " + rn + ": " + std::to_string(nt) + " translations and " + std::to_string(nr) +
                          " rotations (the counts must agree, or one be a single pose)");
  in.count = std::max(nt, nr);
  return in;
}

// Pose i of `in` (no Python object is read: called without the GIL, on
// the threads of a batch).  A bad pose raises ValueError naming it.
RigidPose make_pose(const PoseInput& in, const char* rn, std::size_t i) {
  const std::size_t it = in.t.size() == 1 ? 0 : i;
  try {
    if (!in.quaternions.empty()) {
      const std::array<long long, 4>& d = in.quaternions[in.quaternions.size() == 1 ? 0 : i];
      const std::array<std::int64_t, 4> small{static_cast<std::int64_t>(d[0]), static_cast<std::int64_t>(d[1]),
                                               static_cast<std::int64_t>(d[2]), static_cast<std::int64_t>(d[3])};
      if (in.t.size() == 0) return RigidPose::quaternion64(small, Vec3d{0, 0, 0});
      if (in.t.is_double(it)) return RigidPose::quaternion64(small, in.t.approx(it));
      thread_local Quaternion q;  // its integers' storage reused from pose to pose (no allocation)
      for (int k = 0; k < 4; ++k) mpz_set_si(q[k].get_mpz_t(), static_cast<long>(d[k]));
      return RigidPose::quaternion(q, in.t.exact(it));
    }
    static const std::array<double, 9> id{1, 0, 0, 0, 1, 0, 0, 0, 1};
    const std::array<double, 9>& m = in.matrices.empty() ? id : in.matrices[in.matrices.size() == 1 ? 0 : i];
    if (in.t.size() == 0) return RigidPose::matrix(m, Vec3d{0, 0, 0});
    if (in.t.is_double(it)) return RigidPose::matrix(m, in.t.approx(it));
    return RigidPose::matrix(m, in.t.exact(it));
  } catch (const UsageError& e) {
    throw py::value_error(item(rn, in.matrices.size() == 1 || in.quaternions.size() == 1 ? 0 : i) + ": " + e.what());
  }
}

// The poses of a and b of collide_rigid / distance_rigid: each an input of
// N poses or of one, the larger count N, and the thread count (0: one per
// core).
struct RigidPoses {
  unsigned threads = 0;
  PoseInput b, a;
  std::size_t n = 1;
  static unsigned thread_count(std::optional<long long> t) {
    if (t && *t < 1) throw py::value_error("threads must be at least 1 (or None: one per core)");
    return t ? static_cast<unsigned>(*t) : 0u;
  }
  RigidPoses(py::handle tb, py::handle rb, py::handle ta, py::handle ra, std::optional<long long> t)
      : threads(thread_count(t)), b(to_pose_input(tb, rb, "t_b", "r_b")), a(to_pose_input(ta, ra, "t_a", "r_a")) {
    if (a.count != 1 && b.count != 1 && a.count != b.count)
      throw py::value_error("poses of a and b: " + std::to_string(a.count) + " and " + std::to_string(b.count) +
                            " (the counts must agree, or one be a single pose)");
    n = std::max(a.count, b.count);
  }
};

// The poses of a batch, made on demand on the batch's threads (no vector of
// N poses): an input of one pose for all is built once, here.
class PoseSource {
 public:
  explicit PoseSource(const RigidPoses& p) : p_(p) {
    if (p.a.count == 1) single_[0] = make_pose(p.a, "r_a", 0);
    if (p.b.count == 1) single_[1] = make_pose(p.b, "r_b", 0);
  }
  const RigidPose& operator()(std::size_t i, int body, RigidPose& scratch) const {
    if (single_[body]) return *single_[body];
    scratch = body == 0 ? make_pose(p_.a, "r_a", i) : make_pose(p_.b, "r_b", i);
    return scratch;
  }
  RigidPoseSource source() const {
    return [this](std::size_t i, int body, RigidPose& scratch) -> const RigidPose& { return (*this)(i, body, scratch); };
  }

 private:
  const RigidPoses& p_;
  std::optional<RigidPose> single_[2];
};

// The exact values of each answer of a batch (exact_values), in blocks of
// consecutive poses on `threads` threads, each pose made again by `source`.
template <class Answer>
auto batch_exact_values(const RigidBody& a, const RigidBody& b, const PoseSource& source,
                        const std::vector<Answer>& out, unsigned threads) {
  using Exact = decltype(exact_values(a, std::declval<const RigidPose&>(), b, std::declval<const RigidPose&>(), out[0]));
  const std::size_t n = out.size(), block = 64, blocks = (n + block - 1) / block;
  std::vector<Exact> values(n);
  parallel_for(blocks, threads, [&](std::size_t k) {
    RigidPose scratch_a, scratch_b;
    for (std::size_t i = k * block; i < std::min(n, (k + 1) * block); ++i)
      values[i] = exact_values(a, source(i, 0, scratch_a), b, source(i, 1, scratch_b), out[i]);
  });
  return values;
}

struct WitnessPy {
  Witness w;
};

const char* kModuleDoc = R"(Exact Minkowski sums of polyhedra in 3D (convex and non-convex solids), and exact proximity queries.

Every computation is exact: coordinates are rationals (float inputs are
taken as the exact values of the doubles, Decimal ones as their exact
values; complex numbers and numpy.longdouble are refused), every geometric
decision is the sign of an exact polynomial.  Exact results are Python ints and
fractions.Fraction; float64 arrays (Polytope.vertices) are the nearest
doubles, for plotting and numpy work.
)";

const char* kMinkowskiSumDoc = R"(The Minkowski sum a ⊕ b = {x + y : x in a, y in b}, exactly.

a and b are Polytope objects, file paths or catalog names ("cube",
"sphere:4@rot:5", see load()).  The result is a Sum: a Polytope that also
records the method used, vertex_origin (each vertex is the sum of vertex
vertex_origin[v, 0] of a and vertex vertex_origin[v, 1] of b) and
facet_provenance (the faces of a and b behind each facet).

Every method gives the same polytope (the same vertices and facets); they
differ in speed (what a summary says --json reports is Sum.counters and
Sum.facet_provenance here):
{methods}
"auto" picks walk, the output-sensitive method, for every pair.  Use
another method to compare or to cross-check; "chms" (the hull of all
pairwise vertex sums) is the slow, simple reference.

Non-convex solids: when a or b is a Solid, or a name that is not a convex
polytope (a file or a catalog solid such as "tube", validated as a closed
solid), the sum is that of 'minksum sum' for a non-convex pair (the
boundary sweep, docs/nonconvex.md) and the result is a SolidSum: a Solid
(its exact boundary and volume) with the report the command prints
(pieces, culled and candidate facets, clips, the phases' seconds).  The
method then sums the sweep's pieces: walk (also for "auto" and the
methods other than chms) or chms.  A Polytope given with a Solid is taken
as the convex solid it is.

Sweeps: a or b may be a ConvexSet (a point, a segment or a flat convex
polygon), or a name that is one ("segment:0,0,0:1,2,3", a file holding one
face), docs/sweeps.md: a polytope ⊕ a segment is the solid it sweeps.  A
full-dimensional result is a Sum whose route says how it was made (its
vertex_origin and facet_provenance are then empty); a lower-dimensional one
is a ConvexSet (a segment ⊕ a segment is a parallelogram).  Only walk (also
"auto") and chms take them.  A ConvexSet with a non-convex solid is a
ValueError.  The choice between these kinds is the library's, the same as
'minksum sum' makes.

Raises ValueError for an unknown method, InputError when a file named as an
operand is bad, KeyboardInterrupt when interrupted (Ctrl-C).  The GIL is
released while the sum is computed.)";

// The methods' summaries (the table the command's help uses), each wrapped
// to 76 columns under a two-space indent.
std::string method_docs() {
  std::string out;
  for (const MethodInfo& m : methods()) {
    std::istringstream words(std::string(m.name) + ": " + m.summary);
    std::string line = " ";
    for (std::string w; words >> w;) {
      if (line.size() + 1 + w.size() > 76 && line.size() > 1) {
        out += line + "\n";
        line = "   ";
      }
      line += " " + w;
    }
    out += line + "\n";
  }
  return out;
}

std::string with_methods(std::string text) {
  const std::string key = "{methods}\n";
  text.replace(text.find(key), key.size(), method_docs());
  return text;
}

}  // namespace

PYBIND11_MODULE(_minksum, m) {
  m.doc() = kModuleDoc;

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const NotConvexError& e) {
      raise_input_error("NotConvexError", e);
    } catch (const InputError& e) {
      raise_input_error("InputError", e);
    } catch (const UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const Interrupted&) {
      PyErr_SetString(PyExc_KeyboardInterrupt, "minksum: the sum was interrupted");
    } catch (const py::cast_error& e) {  // an argument of the wrong type met inside a function: not a RuntimeError
      PyErr_SetString(PyExc_TypeError, e.what());
    }
  });

  py::class_<ConvexPolytope, std::shared_ptr<ConvexPolytope>> polytope(m, "Polytope", R"(A convex polytope with exact rational vertex coordinates.

Polytope(vertices, faces=None)

vertices: an (n, 3) numpy array (of floats of at most 64 bits, each value
taken exactly, of integers, or of objects taken as below) or a sequence of (x, y, z) triples of exact numbers (int,
fractions.Fraction, decimal.Decimal, float: the exact value of the double,
numpy integer and float scalars, or text such as "1/3").  Complex numbers and
numpy.longdouble are refused with TypeError (nothing is rounded).  faces: polygons as sequences of vertex indices; without
faces, the polytope is the exact convex hull of the vertices.  With faces,
the mesh must be a closed, exactly convex surface: coplanar facets are
merged, equal vertices welded, unused vertices dropped, and an inward-facing
mesh is turned outward.

Raises InputError (NotConvexError for a surface that is not exactly convex)
when the data is not a convex polytope, ValueError for malformed arguments,
TypeError for arguments of the wrong type.  Polytopes are immutable, safe to
share between threads, and picklable.)");
  polytope
      .def(py::init([](py::object vertices, py::object faces) {
             return std::make_shared<ConvexPolytope>(polytope_from(vertices, faces));
           }),
           py::arg("vertices"), py::arg("faces") = py::none())
      .def_static(
          "hull",
          [](py::object points) {
            return std::make_shared<ConvexPolytope>(polytope_from(points, py::none(), "points"));
          },
          py::arg("points"), "The exact convex hull of an (n, 3) array or a sequence of exact triples.")
      .def_property_readonly(
          "vertices", [](py::object self) { return vertices_view(py::cast<const ConvexPolytope&>(self), self); },
          "The vertices as a read-only float64 (n, 3) array: a view of the polytope's own storage (no copy).\n"
          "Each entry is the nearest double of the exact coordinate (exact when coordinates_are_doubles).")
      .def_property_readonly("coordinates_are_doubles", &ConvexPolytope::coordinates_are_doubles,
                             "True when every coordinate is exactly a double (then vertices is exact).")
      .def(
          "exact_vertices",
          [](const ConvexPolytope& p) {
            py::list out;
            for (std::size_t i = 0; i < p.num_vertices(); ++i) out.append(to_fractions(p.coordinates().exact(i)));
            return out;
          },
          "The exact vertices: a list of (x, y, z) tuples of fractions.Fraction.")
      .def_property_readonly(
          "faces",
          [](const ConvexPolytope& p) {
            py::list out;
            for (Index f = 0; f < p.num_facets(); ++f) out.append(index_array(p.facet_vertices(f)));
            return out;
          },
          "The facets: one int64 array of vertex indices per facet, counter-clockwise seen from outside.")
      .def(
          "triangles",
          [](const ConvexPolytope& p) {
            std::size_t count = 0;
            for (Index f = 0; f < p.num_facets(); ++f) count += p.facet_degree(f) - 2;
            py::array_t<std::int64_t> a({static_cast<py::ssize_t>(count), py::ssize_t{3}});
            auto r = a.mutable_unchecked<2>();
            py::ssize_t k = 0;
            for (Index f = 0; f < p.num_facets(); ++f) {
              const auto loop = p.facet_vertices(f);
              for (std::size_t i = 1; i + 1 < loop.size(); ++i, ++k) {
                r(k, 0) = loop[0];
                r(k, 1) = loop[i];
                r(k, 2) = loop[i + 1];
              }
            }
            return a;
          },
          "The facets fan-triangulated, as an int64 (m, 3) array of vertex indices, counter-clockwise\n"
          "seen from outside (for renderers: trimesh.Trimesh(p.vertices, p.triangles())).")
      .def(
          "planes",
          [](const ConvexPolytope& p) {
            py::list out;
            for (Index f = 0; f < p.num_facets(); ++f) {
              const Plane& pl = p.plane(f);
              out.append(py::make_tuple(to_int(pl.a), to_int(pl.b), to_int(pl.c), to_int(pl.d)));
            }
            return out;
          },
          "The facet planes a*x + b*y + c*z = d, one (a, b, c, d) tuple of Python ints per facet, with\n"
          "outward normal (a, b, c) and gcd(a, b, c, d) = 1: equal planes compare equal.")
      .def_property_readonly("num_vertices", &ConvexPolytope::num_vertices)
      .def_property_readonly("num_edges", &ConvexPolytope::num_edges)
      .def_property_readonly("num_facets", &ConvexPolytope::num_facets)
      .def(
          "volume",
          [](const ConvexPolytope& p) {
            Rational v;
            {
              py::gil_scoped_release nogil;
              v = p.volume();
            }
            return to_fraction(v);
          },
          "The exact volume, a fractions.Fraction.")
      .def(
          "translated",
          [](const ConvexPolytope& p, py::object t) {
            const Point3 v = to_point(t, "t");
            py::gil_scoped_release nogil;
            return std::make_shared<ConvexPolytope>(p.translated(v));
          },
          py::arg("t"), "The polytope translated by t (exact).")
      .def(
          "negated",
          [](const ConvexPolytope& p) {
            py::gil_scoped_release nogil;
            return std::make_shared<ConvexPolytope>(p.negated());
          },
          "-P, the point reflection.")
      .def(
          "save",
          [](const ConvexPolytope& p, py::object path, bool exact, bool binary) {
            const std::string file = py::cast<std::string>(py::module_::import("os").attr("fsdecode")(path));
            WriteOptions w;
            w.exact = exact;
            w.binary = binary;
            try {
              py::gil_scoped_release nogil;
              write_polytope(file, p, w);
            } catch (const InputError& e) {  // the file system refused: not bad data
              PyErr_SetString(PyExc_OSError, e.what());
              throw py::error_already_set();
            }
          },
          py::arg("path"), py::arg("exact") = false, py::arg("binary") = false,
          "Write the polytope to path (.off, .obj, .ply, .stl or .wrl, by extension), atomically.\n"
          "exact=True writes exact rationals (.off, .obj and .wrl only); otherwise each coordinate is\n"
          "the shortest text that reads back to its nearest double.  binary=True: binary .ply/.stl.\n"
          "Raises ValueError for an unknown extension or a request the format cannot honour, OSError\n"
          "when the file cannot be written.")
      .def("__repr__",
           [](const ConvexPolytope& p) {
             return "<minksum.Polytope: " + std::to_string(p.num_vertices()) + " vertices, " +
                    std::to_string(p.num_edges()) + " edges, " + std::to_string(p.num_facets()) + " facets>";
           })
      .def(py::pickle([](const ConvexPolytope& p) { return polytope_state(p); },
                      [](const py::tuple& t) { return std::make_shared<ConvexPolytope>(polytope_from_state(t)); }));

  py::class_<Sum, std::shared_ptr<Sum>, ConvexPolytope>(m, "Sum", R"(The result of minkowski_sum: a Polytope with its history.

method: the method that computed it.  vertex_origin: int64 (n, 2) array, the
vertex of a and the vertex of b whose sum is each vertex.  facet_provenance:
for each facet, (kind, feature of a, feature of b) with kind one of
"translated" (facet of a + vertex of b), "corner" (vertex of a + facet of b),
"edge" (edge + edge), "facet_edge", "facet_facet", and features as
("vertex" | "edge" | "facet", index).  seconds: the computation alone.
counters: operation counts some methods record.)")
      .def_property_readonly("method", [](const Sum& s) { return method_name(s.method); })
      .def_property_readonly("route",
                             [](const Sum& s) -> py::object {
                               if (!s.route) return py::none();
                               return py::str(s.route);
                             },
                             "None for a sum of two polytopes; for a sum with a point, segment or polygon (a sweep,\n"
                             "docs/sweeps.md) how it was made: \"translation\", \"sweep\" or \"hull\" (vertex_origin and\n"
                             "facet_provenance are then empty).")
      .def_property_readonly("vertex_origin",
                             [](const Sum& s) {
                               py::array_t<std::int64_t> a({static_cast<py::ssize_t>(s.vertex_origin.size()),
                                                            py::ssize_t{2}});
                               auto r = a.mutable_unchecked<2>();
                               for (std::size_t i = 0; i < s.vertex_origin.size(); ++i) {
                                 r(static_cast<py::ssize_t>(i), 0) = s.vertex_origin[i].first;
                                 r(static_cast<py::ssize_t>(i), 1) = s.vertex_origin[i].second;
                               }
                               return a;
                             })
      .def_property_readonly("facet_provenance", [](Sum& s) {
        {
          py::gil_scoped_release nogil;
          s.facet_provenance_list();
        }
        return provenance_list(s);
      })
      .def_readonly("seconds", &Sum::seconds)
      .def_property_readonly("counters",
                             [](const Sum& s) {
                               py::dict d;
                               for (const auto& [k, v] : s.counters) d[py::str(k)] = v;
                               return d;
                             })
      .def("__repr__",
           [](const Sum& s) {
             return "<minksum.Sum (" + std::string(method_name(s.method)) + "): " + std::to_string(s.num_vertices()) +
                    " vertices, " + std::to_string(s.num_edges()) + " edges, " + std::to_string(s.num_facets()) +
                    " facets>";
           })
      .def(py::pickle(
          [](Sum& s) {
            {
              py::gil_scoped_release nogil;
              s.facet_provenance_list();
            }
            py::list origin, prov;
            for (const auto& [i, j] : s.vertex_origin) origin.append(py::make_tuple(i, j));
            for (const auto& p : s.provenance)
              prov.append(py::make_tuple(int(p.a.dim), p.a.index, int(p.b.dim), p.b.index));
            return py::make_tuple(polytope_state(s), method_name(s.method), origin, prov, s.seconds,
                                  py::cast(s.counters), s.route ? py::str(s.route) : py::object(py::none()));
          },
          [](const py::tuple& t) {
            if (t.size() != 6 && t.size() != 7) throw py::value_error("Sum: bad pickled state");
            auto s = std::make_shared<Sum>();
            static_cast<ConvexPolytope&>(*s) = polytope_from_state(t[0]);
            s->method = to_method(py::cast<std::string>(t[1]));
            for (py::handle o : t[2]) {
              auto p = py::cast<std::pair<Index, Index>>(o);
              s->vertex_origin.push_back(p);
            }
            for (py::handle o : t[3]) {
              auto v = py::cast<std::array<Index, 4>>(o);
              s->provenance.push_back({Feature{FeatureDim(v[0]), v[1]}, Feature{FeatureDim(v[2]), v[3]}});
            }
            s->seconds = py::cast<double>(t[4]);
            s->counters = py::cast<std::vector<std::pair<std::string, long long>>>(t[5]);
            if (t.size() == 7 && !t[6].is_none())
              s->route = literal(py::cast<std::string>(t[6]), {"polytopes", "translation", "sweep", "hull"}, "Sum");
            return s;
          }));

  py::class_<SolidPy, std::shared_ptr<SolidPy>>(m, "Solid", R"(A closed polyhedral solid, convex or not, of any genus, with exact coordinates.

Solid(vertices, faces)

vertices: as for Polytope (an (n, 3) float64 array, each double taken
exactly, an integer array, or a sequence of exact triples: int, Fraction,
Decimal, float, text such as "1/3").  faces: polygons as sequences of vertex
indices, or an (m, k) integer array (triangles: (m, 3)), counter-clockwise
seen from outside.  The mesh is validated exactly as 'minksum sum' validates
a non-convex operand (validate_solid): faces of at least three distinct
vertices, planar and simple; every edge shared by two faces in opposite
directions; every vertex one fan of faces; no self-intersection; the shells
oriented as their nesting requires.  Equal vertices are welded and unused
ones dropped.  Solid.load(name) reads a file or builds a catalog solid.

Raises InputError (file "", place, problem: the message the command prints)
when the mesh is not a valid closed solid, ValueError for malformed
arguments, TypeError for arguments of the wrong type.)")
      .def(py::init([](py::object vertices, py::object faces) {
             Mesh mesh;
             mesh.points = to_points(vertices, "vertices");
             read_faces(mesh, faces);
             py::gil_scoped_release nogil;
             return solid_from(validate_solid(mesh, ""), "");
           }),
           py::arg("vertices"), py::arg("faces"))
      .def_static(
          "load",
          [](py::object spec) {
            const NamedOperand o = to_operand(spec, "path_or_name");
            if (std::holds_alternative<PolytopePtr>(o))
              throw py::type_error("Solid.load: expected a file path or a catalog name");
            const std::string name = std::get<std::string>(o);
            py::gil_scoped_release nogil;
            return solid_from(load_solid(name), name);
          },
          py::arg("path_or_name"),
          "A solid from a file (.off, .obj, .ply, .stl, .wrl) or the catalog (\"tube\", \"cube\", ...): a convex\n"
          "polytope as the solid it is, any other mesh validated as a closed solid.  Raises InputError as\n"
          "load() does, ValueError for a name that is neither a file nor a catalog spec.")
      .def_property_readonly(
          "vertices", [](const SolidPy& s) { return points_array(s.faces.points); },
          "The vertices as a float64 (n, 3) array: the nearest double of each exact coordinate (a copy).")
      .def(
          "exact_vertices",
          [](const SolidPy& s) {
            py::list out;
            for (std::size_t i = 0; i < s.faces.points.size(); ++i) out.append(to_fractions(s.faces.points.exact(i)));
            return out;
          },
          "The exact vertices: a list of (x, y, z) tuples of fractions.Fraction.")
      .def_property_readonly(
          "faces",
          [](const SolidPy& s) {
            py::list out;
            for (const auto& f : s.faces.faces) out.append(index_array(f));
            return out;
          },
          "The faces: one int64 array of vertex indices per face, counter-clockwise seen from outside.")
      .def(
          "triangles",
          [](const SolidPy& s) {
            Mesh t;
            {
              py::gil_scoped_release nogil;
              t = s.triangles();
            }
            return triangle_array(t);
          },
          "The faces cut into triangles (exact ear clipping), an int64 (m, 3) array of vertex indices\n"
          "counter-clockwise seen from outside (trimesh.Trimesh(s.vertices, s.triangles())).")
      .def_property_readonly("num_vertices", [](const SolidPy& s) { return s.faces.points.size(); })
      .def_property_readonly("num_edges", [](const SolidPy& s) { return solid_stats(s.faces).edges; })
      .def_property_readonly("num_facets", [](const SolidPy& s) { return s.faces.faces.size(); })
      .def_property_readonly(
          "is_convex",
          [](SolidPy& s) {
            py::gil_scoped_release nogil;
            return s.is_convex();
          },
          "True when the solid is exactly a convex polytope (a sum's result is validated as a solid first).")
      .def(
          "volume", [](const SolidPy& s) { return to_fraction(s.volume); }, "The exact volume, a fractions.Fraction.")
      .def_property_readonly(
          "stats",
          [](const SolidPy& s) {
            SolidStats c;
            {
              py::gil_scoped_release nogil;
              c = solid_stats(s.faces);
            }
            py::dict d;
            d["vertices"] = c.vertices;
            d["edges"] = c.edges;
            d["facets"] = c.facets;
            d["volume"] = to_fraction(s.volume);
            d["volume_float"] = to_double(s.volume);
            d["genus"] = c.genus;
            d["shells"] = c.shells;
            d["bounding_box"] = py::make_tuple(to_fractions(c.min), to_fractions(c.max));
            return d;
          },
          "What 'minksum stats' prints of a solid, as a dict: vertices, edges, facets (ints), volume (exact\n"
          "Fraction), volume_float (its nearest double), genus (the sum of the shells' genera: a torus 1),\n"
          "shells (connected components of the surface), bounding_box ((min, max), exact Fraction triples).")
      .def(
          "save",
          [](const SolidPy& s, py::object path, bool exact, bool binary) -> py::object {
            const std::string file = py::cast<std::string>(py::module_::import("os").attr("fsdecode")(path));
            WriteOptions w;
            w.exact = exact;
            w.binary = binary;
            RoundedSolid r;
            try {
              py::gil_scoped_release nogil;
              if (s.convex_written) {
                RoundingReport p;
                write_polytope(file, *s.convex_written, w, &p);
                r.rounded_coordinates = p.coordinates;
                r.max_displacement = p.max_displacement;
              } else {
                r = write_solid(file, s.faces, w);
              }
            } catch (const RoundingError& e) {
              throw py::value_error(std::string("cannot write ") + file + ": " + e.what() +
                                    "; exact=True writes exact rationals (.off, .obj, .wrl)");
            } catch (const UsageError&) {
              throw;  // an unknown extension, exact rationals in STL or PLY: ValueError
            } catch (const InputError& e) {  // the file system refused: not bad data
              PyErr_SetString(PyExc_OSError, e.what());
              throw py::error_already_set();
            }
            if (!r.rounded_coordinates && r.max_displacement == 0) return py::none();
            py::dict d;
            d["coordinates"] = r.rounded_coordinates;
            d["max_displacement"] = r.max_displacement;
            d["grid"] = r.grid;
            return d;
          },
          py::arg("path"), py::arg("exact") = false, py::arg("binary") = false,
          "Write the solid's faces to path (.off, .obj, .ply, .stl or .wrl, by extension), atomically, as\n"
          "'minksum sum -o' writes a non-convex sum (the erosion, opening or closing of a convex a as a convex\n"
          "polytope, as 'minksum erode|open|close -o' writes it).  exact=True writes exact rationals (.off, .obj and\n"
          ".wrl only); otherwise coordinates that are not doubles (binary=True .stl: 32-bit floats) are\n"
          "rounded and the surface written as a valid closed solid without self-intersection (checked\n"
          "exactly; docs/nonconvex.md, \"Output\"), STL as triangles.  Returns None when nothing moved, else\n"
          "a dict of what rounding did (coordinates, max_displacement, grid), as 'rounding' in --json.\n"
          "Raises ValueError for an unknown extension, a request the format cannot honour or a solid it\n"
          "cannot represent, OSError when the file cannot be written.")
      .def(py::pickle([](const SolidPy& s) { return solid_state(s); },
                      [](const py::tuple& t) {
                        auto s = std::make_shared<SolidPy>();
                        solid_from_state(*s, t);
                        return s;
                      }))
      .def("__repr__", [](const SolidPy& s) {
        const SolidStats c = solid_stats(s.faces);
        return "<minksum.Solid: " + std::to_string(c.vertices) + " vertices, " + std::to_string(c.edges) +
               " edges, " + std::to_string(c.facets) + " faces>";
      });

  py::class_<SetPy, std::shared_ptr<SetPy>>(m, "ConvexSet", R"(A point, a segment or a flat convex polygon, with exact coordinates: an operand of a sweep.

ConvexSet(points): the exact convex hull of the points in whatever dimension
they span: one point, a segment, a polygon (or, for points spanning 3
dimensions, a polytope).  points as for Polytope: an (n, 3) float64 array
(each double taken exactly), an integer array, or a sequence of exact
triples (int, Fraction, Decimal, float, text such as "1/3").
ConvexSet.load(name) reads a file holding one face or builds a catalog set
("point:1,2,3", "segment:0,0,0:1,0,0", "polygon:6", "square", with @
transforms).

minkowski_sum(a, b) takes a ConvexSet as either operand with a Polytope, a
ConvexSet, a file or a catalog name (docs/sweeps.md: a polytope ⊕ a segment
is the solid the polytope sweeps along it): the result is a Sum when it is
full-dimensional (its route says how it was made), else a ConvexSet whose
method, route and seconds say how it was computed.  A ConvexSet with a
non-convex Solid is a ValueError.)")
      .def(py::init([](py::object points) {
             const PointList pts = to_points(points, "points");
             py::gil_scoped_release nogil;
             auto out = std::make_shared<SetPy>();
             out->set = ConvexSet::hull(pts);
             return out;
           }),
           py::arg("points"))
      .def_static(
          "load",
          [](py::object spec, bool hull) {
            const NamedOperand o = to_operand(spec, "path_or_name");
            if (std::holds_alternative<PolytopePtr>(o))
              throw py::type_error("ConvexSet.load: expected a file path or a catalog name");
            const std::string name = std::get<std::string>(o);
            py::gil_scoped_release nogil;
            auto out = std::make_shared<SetPy>();
            out->set = load_convex_set(name, hull);
            out->name = name;
            return out;
          },
          py::arg("path_or_name"), py::arg("hull") = false,
          "A point, segment or polygon from the catalog (\"segment:0,0,0:1,2,3\", \"polygon:6\", \"square\") or a\n"
          "file holding one face; a polytope for any other valid convex mesh.  hull=True takes the exact hull\n"
          "of the points in whatever dimension they span.  Raises InputError for bad data, ValueError for a\n"
          "name that is neither a file nor a catalog spec.")
      .def_property_readonly("dimension", [](const SetPy& s) { return s.set.dimension(); },
                             "0 (a point), 1 (a segment), 2 (a polygon) or 3 (a polytope).")
      .def_property_readonly("kind", [](const SetPy& s) { return std::string(dimension_name(s.set.dimension())); },
                             "\"point\", \"segment\", \"polygon\" or \"polytope\".")
      .def_property_readonly(
          "vertices",
          [](const SetPy& s) {
            const std::vector<Point3>& v = s.set.vertices();
            py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
            auto r = a.mutable_unchecked<2>();
            for (std::size_t i = 0; i < v.size(); ++i) {
              const Vec3d d = to_double(v[i]);
              r(static_cast<py::ssize_t>(i), 0) = d.x;
              r(static_cast<py::ssize_t>(i), 1) = d.y;
              r(static_cast<py::ssize_t>(i), 2) = d.z;
            }
            return a;
          },
          "The vertices as a float64 (n, 3) array (a polygon's in the order of its loop): the nearest doubles.")
      .def(
          "exact_vertices",
          [](const SetPy& s) {
            py::list out;
            for (const Point3& p : s.set.vertices()) out.append(to_fractions(p));
            return out;
          },
          "The exact vertices: a list of (x, y, z) tuples of fractions.Fraction.")
      .def_property_readonly("num_vertices", [](const SetPy& s) { return s.set.num_vertices(); })
      .def_property_readonly("num_edges", [](const SetPy& s) { return s.set.num_edges(); })
      .def_property_readonly("num_facets", [](const SetPy& s) { return s.set.num_facets(); })
      .def(
          "volume", [](const SetPy& s) { return to_fraction(s.set.volume()); },
          "The exact volume, a fractions.Fraction (0 below dimension 3).")
      .def(
          "area_squared", [](const SetPy& s) { return to_fraction(s.set.area_squared()); },
          "The exact area of a polygon, squared (kept squared so that it stays rational); 0 otherwise.")
      .def_property_readonly("method",
                             [](const SetPy& s) -> py::object {
                               if (!s.method) return py::none();
                               return py::str(s.method);
                             },
                             "A sum's method (walk or chms); None for a set that is not a sum's result.")
      .def_property_readonly("route",
                             [](const SetPy& s) -> py::object {
                               if (!s.route) return py::none();
                               return py::str(s.route);
                             },
                             "How a sum was made (\"translation\", \"sweep\", \"hull\"); None otherwise.")
      .def_readonly("seconds", &SetPy::seconds, "A sum's computation time (0 otherwise).")
      .def(py::pickle(
          [](const SetPy& s) {
            const PointList pts(s.set.vertices());
            return py::make_tuple(exact_points_state(pts), s.name, s.method ? py::str(s.method) : py::object(py::none()),
                                  s.route ? py::str(s.route) : py::object(py::none()), s.seconds);
          },
          [](const py::tuple& t) {
            if (t.size() != 5) throw py::value_error("ConvexSet: bad pickled state");
            auto s = std::make_shared<SetPy>();
            s->set = ConvexSet::hull(to_points(t[0], "vertices"));  // a polygon's vertices give it back
            s->name = py::cast<std::string>(t[1]);
            if (!t[2].is_none()) s->method = method_name(to_method(py::cast<std::string>(t[2])));
            if (!t[3].is_none())
              s->route = literal(py::cast<std::string>(t[3]), {"polytopes", "translation", "sweep", "hull"}, "ConvexSet");
            s->seconds = py::cast<double>(t[4]);
            return s;
          }))
      .def("__repr__", [](const SetPy& s) {
        return "<minksum.ConvexSet: a " + std::string(dimension_name(s.set.dimension())) + ", " +
               std::to_string(s.set.num_vertices()) + " vertices>";
      });

  py::class_<SolidSum, std::shared_ptr<SolidSum>, SolidPy>(m, "SolidSum", R"(The result of minkowski_sum with a non-convex operand: a Solid with its report.

The boundary of a ⊕ b (exact polygons; where the sum touches itself the
boundary is kept as it is, an edge of four faces) and what 'minksum sum'
prints of the sum: method ("sweep"), swept ("a", "b" or None), pieces (the
polygons swept, coplanar triangles merged, and the convex pieces of the
other operand, (a, b)), pairs,
pair_facets, candidate_facets, culled_facets, clips, shells,
non_manifold_edges, dropped_components, phases (seconds of "decompose",
"pairs", "union", "boundary") and seconds (their sum).  erode, opening and
closing return one too: operation is then "erosion", "opening" or "closing"
(else "sum"), empty is True when nothing is left (no faces, volume 0), and
the counts and seconds are those of all the steps together.)")
      .def_property_readonly("method", [](const SolidSum& s) { return std::string(s.report.method); })
      .def_property_readonly("operation", [](const SolidSum& s) { return std::string(s.report.operation); })
      .def_property_readonly("empty", [](const SolidSum& s) { return s.faces.faces.empty(); })
      .def_property_readonly("swept",
                             [](const SolidSum& s) -> py::object {
                               if (!s.report.swept) return py::none();
                               return py::str(std::string(1, s.report.swept));
                             })
      .def_property_readonly("pieces", [](const SolidSum& s) { return py::make_tuple(s.report.pieces_a, s.report.pieces_b); })
      .def_property_readonly("pairs", [](const SolidSum& s) { return s.report.pairs; })
      .def_property_readonly("pair_facets", [](const SolidSum& s) { return s.report.pair_facets; })
      .def_property_readonly("candidate_facets", [](const SolidSum& s) { return s.report.candidate_facets; })
      .def_property_readonly("culled_facets", [](const SolidSum& s) { return s.report.culled_facets; })
      .def_property_readonly("clips", [](const SolidSum& s) { return s.report.clips; })
      .def_property_readonly("shells", [](const SolidSum& s) { return s.report.shells; })
      .def_property_readonly("non_manifold_edges", [](const SolidSum& s) { return s.report.non_manifold_edges; })
      .def_property_readonly("dropped_components", [](const SolidSum& s) { return s.report.dropped_components; })
      .def_property_readonly("phases",
                             [](const SolidSum& s) {
                               py::dict d;
                               d["decompose"] = s.report.seconds_decompose;
                               d["pairs"] = s.report.seconds_pairs;
                               d["union"] = s.report.seconds_union;
                               d["boundary"] = s.report.seconds_boundary;
                               return d;
                             })
      .def_property_readonly("seconds", [](const SolidSum& s) { return s.report.seconds(); })
      .def(py::pickle(
          [](const SolidSum& s) {
            const NonconvexSum& r = s.report;
            return py::make_tuple(
                solid_state(s),
                py::make_tuple(r.method, std::string(r.swept ? 1 : 0, r.swept), method_name(r.pair_method),
                               r.pieces_from_maps, r.pieces_a, r.pieces_b, r.pairs, r.candidate_facets,
                               r.culled_facets, r.dropped_components, r.pair_vertices, r.pair_facets, r.clips, r.shells,
                               r.non_manifold_edges, r.operation),
                py::make_tuple(r.seconds_decompose, r.seconds_pairs, r.seconds_union, r.seconds_boundary));
          },
          [](const py::tuple& t) {
            if (t.size() != 3) throw py::value_error("SolidSum: bad pickled state");
            auto s = std::make_shared<SolidSum>();
            solid_from_state(*s, py::cast<py::tuple>(t[0]));
            const auto r = py::cast<py::tuple>(t[1]);
            const auto sec = py::cast<py::tuple>(t[2]);
            if (r.size() != 16 || sec.size() != 4) throw py::value_error("SolidSum: bad pickled state");
            NonconvexSum& n = s->report;
            n.method = literal(py::cast<std::string>(r[0]), {"sweep", "decomposition"}, "SolidSum");
            const std::string swept = py::cast<std::string>(r[1]);
            n.swept = swept.empty() ? 0 : swept[0];
            n.pair_method = to_method(py::cast<std::string>(r[2]));
            n.pieces_from_maps = py::cast<bool>(r[3]);
            std::size_t* counts[] = {&n.pieces_a,      &n.pieces_b,           &n.pairs,         &n.candidate_facets,
                                     &n.culled_facets, &n.dropped_components, &n.pair_vertices, &n.pair_facets,
                                     &n.clips,         &n.shells,             &n.non_manifold_edges};
            for (std::size_t i = 0; i < std::size(counts); ++i) *counts[i] = py::cast<std::size_t>(r[4 + i]);
            n.operation =
                literal(py::cast<std::string>(r[15]), {"sum", "erosion", "opening", "closing"}, "SolidSum");
            n.seconds_decompose = py::cast<double>(sec[0]);
            n.seconds_pairs = py::cast<double>(sec[1]);
            n.seconds_union = py::cast<double>(sec[2]);
            n.seconds_boundary = py::cast<double>(sec[3]);
            n.volume = s->volume;
            return s;
          }))
      .def("__repr__", [](const SolidSum& s) {
        const SolidStats c = solid_stats(s.faces);
        return "<minksum.SolidSum (" + std::string(s.report.method) + "): " + std::to_string(c.vertices) +
               " vertices, " + std::to_string(c.edges) + " edges, " + std::to_string(c.facets) + " faces>";
      });

  m.def(
      "load",
      [](py::object spec, bool hull) {
        const NamedOperand o = to_operand(spec, "path_or_name");
        if (std::holds_alternative<PolytopePtr>(o)) throw py::type_error("load: expected a file path or a catalog name");
        py::gil_scoped_release nogil;
        return std::const_pointer_cast<ConvexPolytope>(resolve(o, hull));
      },
      py::arg("path_or_name"), py::arg("hull") = false,
      R"(Load a polytope from a file (.off, .obj, .ply, .stl, .wrl) or build a catalog polytope.

A path to an existing file is read; otherwise the text is a catalog spec such
as "cube", "sphere:4", "dioctagonal:17", "random:1000:7", "box:1:2:3" or
"sphere:3@rot:5" (the command 'minksum gen --help' lists the catalog).
hull=True takes the exact convex hull of the file's points instead of
requiring a valid convex mesh.

Raises InputError (file, place, problem) for bad data or an unreadable file,
NotConvexError when the surface is not exactly convex (hull=True accepts it),
ValueError for a name that is neither a file nor a catalog spec.)");

  m.def(
      "minkowski_sum",
      [](py::object a, py::object b, const std::string& method) -> py::object {
        const AnyOperandPy oa = to_any_operand(a, "a"), ob = to_any_operand(b, "b");
        return sum_interruptible(oa, ob, to_method(method));
      },
      py::arg("a"), py::arg("b"), py::arg("method") = "auto", with_methods(kMinkowskiSumDoc).c_str());

  // erode, opening, closing (<minksum/nonconvex.hpp>): a solid A and a convex B.
  auto morphology = [](SumOperation operation) {
    return [operation](py::object a, py::object b, const std::string& method) {
      const AnyOperandPy oa = to_any_operand(a, "a"), ob = to_any_operand(b, "b");
      return sum_interruptible(oa, ob, to_method(method), operation);
    };
  };
  const char* kMorphologyArgs = R"(

a is a Solid, a Polytope, a file path or a catalog name (any closed solid,
convex or not, of any genus, several shells allowed); b must be a convex
polytope (a Polytope, or a Solid or name that is one), the structuring
element.  The result is a SolidSum (operation, the exact boundary and volume,
shells, and the work done, as 'minksum %s --json' reports it).  An empty
result is a SolidSum with empty=True, no faces and volume 0.  method builds
the sweep's pieces: "walk" (also "auto") or "chms"; the same exact result.
Raises ValueError when b is not convex or for an unknown method, InputError
for a bad file, KeyboardInterrupt when interrupted.  The GIL is released
while it runs.)";
  auto morphology_doc = [&](const char* head, const char* command) {
    char buffer[1024];
    std::snprintf(buffer, sizeof buffer, kMorphologyArgs, command);
    return std::string(head) + buffer;
  };
  static const std::string erode_doc = morphology_doc(
      "A ⊖ B = {x : x + B ⊆ A}, exactly: the erosion of solid a by convex b (docs/nonconvex.md).", "erode");
  static const std::string opening_doc = morphology_doc(
      "(A ⊖ B) ⊕ B, exactly: the opening of solid a by convex b, the union of the copies of b inside a (a's convex "
      "edges rounded).",
      "open");
  static const std::string closing_doc = morphology_doc(
      "(A ⊕ B) ⊖ B, exactly: the closing of solid a by convex b (a's concave edges filled: fillets).", "close");
  m.def("erode", morphology(SumOperation::erode), py::arg("a"), py::arg("b"), py::arg("method") = "auto", erode_doc.c_str());
  m.def("opening", morphology(SumOperation::open), py::arg("a"), py::arg("b"), py::arg("method") = "auto", opening_doc.c_str());
  m.def("closing", morphology(SumOperation::close), py::arg("a"), py::arg("b"), py::arg("method") = "auto", closing_doc.c_str());

  m.def(
      "minkowski_sum_many",
      [](py::iterable pairs, std::optional<long long> threads, const std::string& method,
         const std::string& on_error) {
        if (threads && *threads < 1) throw py::value_error("threads must be at least 1 (or None: one per core)");
        if (on_error != "raise" && on_error != "return")
          throw py::value_error("on_error must be 'raise' or 'return', not '" + on_error + "'");
        const Method default_method = to_method(method);
        struct Job {
          AnyOperandPy a, b;
          Method method;
        };
        std::vector<Job> jobs;
        for (py::handle pair : pairs) {
          const std::string where = item("pairs", jobs.size());
          if (!py::isinstance<py::sequence>(pair) || py::isinstance<py::str>(pair) ||
              (py::len(pair) != 2 && py::len(pair) != 3))
            throw py::value_error(where + ": expected (a, b) or (a, b, method)");
          auto t = py::reinterpret_borrow<py::sequence>(pair);
          Job j{to_any_operand(t[0], (where + "[0]").c_str()), to_any_operand(t[1], (where + "[1]").c_str()),
                default_method};
          if (t.size() == 3) {
            if (!py::isinstance<py::str>(t[2]))
              throw py::type_error(where + "[2]: expected a method name (str), got " + type_name(t[2]));
            j.method = to_method(py::cast<std::string>(t[2]));
          }
          jobs.push_back(std::move(j));
        }
        // A convex sum, or the sum with a solid (exactly what minkowski_sum returns).
        std::vector<SumPy> results(jobs.size());
        std::vector<std::exception_ptr> errors(jobs.size());
        std::atomic<bool> cancel{false};
        SumOptions options;
        options.cancel = &cancel;
        run_interruptible(
            [&] {
              parallel_for(jobs.size(), threads ? static_cast<unsigned>(*threads) : 0u, [&](std::size_t i) {
                if (cancel) return;  // interrupted: the pairs not started are skipped
                try {
                  Job& j = jobs[i];
                  results[i] = sum_any(j.a, j.b, j.method, options, 0);
                } catch (...) {
                  errors[i] = std::current_exception();
                }
              });
            },
            cancel);
        py::list out;
        for (std::size_t i = 0; i < jobs.size(); ++i) {
          if (!errors[i]) {
            out.append(std::visit([](const auto& r) { return py::cast(r); }, results[i]));
            continue;
          }
          py::object e = exception_object(errors[i]);
          e.attr("add_note")("minksum.minkowski_sum_many: pairs[" + std::to_string(i) + "]");
          if (on_error == "return") {
            out.append(e);
          } else {
            PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(e.ptr())), e.ptr());
            throw py::error_already_set();
          }
        }
        return out;
      },
      py::arg("pairs"), py::arg("threads") = py::none(), py::arg("method") = "auto", py::arg("on_error") = "raise",
      R"(Many independent Minkowski sums on a pool of C++ threads; the results in input order.

pairs: an iterable of (a, b) or (a, b, method) with a and b Polytope or
Solid objects, file paths or catalog names (names are loaded on the worker
threads; a name that is not a convex polytope is a solid, as in
minkowski_sum).
threads: the number of threads (None: one per hardware thread).  method: the
method of the pairs that do not name one (see minkowski_sum).  Each result is
exactly what minkowski_sum(a, b, method) returns (a Sum, or a SolidSum when
an operand is a solid), whatever the number of threads.

A pair that fails (a bad file, an unknown name): with on_error="raise" the
exception of the first failing pair is raised once every pair is done, with
a note naming the pair ("pairs[7]"); with on_error="return" the exception
object takes the pair's place in the list.  Arguments that are malformed
(not a pair, an unknown method) raise ValueError, and of the wrong type
TypeError, before anything is computed.  The GIL is released during the
whole batch.  Ctrl-C stops the batch: the sums under way stop at their next
report point, the pairs not started are skipped, and KeyboardInterrupt is
raised.)");

  py::class_<WitnessPy>(m, "Witness", R"(Where a proximity query was decided.

facet: the facet of M = P ⊕ (−Q) the query ended on; m: the smallest
feature of M containing the point the answer refers to; p, q: the features
of P and Q behind it (m = p ⊕ −q).  Features are (kind, index) with kind
"vertex", "edge" or "facet" and indices of P and Q as given.)")
      .def_property_readonly("facet", [](const WitnessPy& w) { return w.w.facet; })
      .def_property_readonly("m", [](const WitnessPy& w) { return feature(w.w.m); })
      .def_property_readonly("p", [](const WitnessPy& w) { return feature(w.w.p); })
      .def_property_readonly("q", [](const WitnessPy& w) { return feature(w.w.q); })
      .def("__repr__", [](const WitnessPy& w) {
        return "<minksum.Witness facet " + std::to_string(w.w.facet) + ": m = " + feature_kind(w.w.m.dim) + " " +
               std::to_string(w.w.m.index) + ", p = " + feature_kind(w.w.p.dim) + " " + std::to_string(w.w.p.index) +
               ", q = " + feature_kind(w.w.q.dim) + " " + std::to_string(w.w.q.index) + ">";
      });

  auto status = [](ContactStatus s) { return contact_status_name(s); };
  py::class_<CollisionResult>(m, "CollisionResult", "collide(): status and witness.")
      .def_property_readonly("status", [=](const CollisionResult& r) { return status(r.status); })
      .def_property_readonly("witness", [](const CollisionResult& r) { return WitnessPy{r.witness}; });
  py::class_<DistanceResult>(m, "DistanceResult", R"(distance(): the separation distance.

squared_distance: exact Fraction (0 unless separate); distance: the nearest
double of its square root; point_p, point_q: closest points of P and of the
translated Q (exact Fraction triples; a common point when they touch or
overlap); direction: point_q − point_p.)")
      .def_property_readonly("status", [=](const DistanceResult& r) { return status(r.status); })
      .def_property_readonly("squared_distance", [](const DistanceResult& r) { return to_fraction(r.squared_distance()); })
      .def_property_readonly("distance", [](const DistanceResult& r) { return r.distance(); })
      .def_property_readonly("point_p", [](const DistanceResult& r) { return to_fractions(r.point_p()); })
      .def_property_readonly("point_q", [](const DistanceResult& r) { return to_fractions(r.point_q()); })
      .def_property_readonly("direction", [](const DistanceResult& r) { return to_fractions(r.direction()); })
      .def_property_readonly("witness", [](const DistanceResult& r) { return WitnessPy{r.witness}; });
  py::class_<DepthResult>(m, "DepthResult", R"(depth(): the penetration depth.

squared_depth: exact Fraction (0 unless penetrating); depth: the nearest
double of its square root; direction: a minimal translation of P that makes
the bodies touch (exact Fraction triple, zero unless penetrating).)")
      .def_property_readonly("status", [=](const DepthResult& r) { return status(r.status); })
      .def_property_readonly("squared_depth", [](const DepthResult& r) { return to_fraction(r.squared_depth()); })
      .def_property_readonly("depth", [](const DepthResult& r) { return r.depth(); })
      .def_property_readonly("direction", [](const DepthResult& r) { return to_fractions(r.direction()); })
      .def_property_readonly("witness", [](const DepthResult& r) { return WitnessPy{r.witness}; });
  py::class_<DirectionalDepthResult>(m, "DirectionalDepthResult", R"(directional_depth(): depth along d.

t: the exact Fraction α ≥ 0, the smallest with P translated by α·d no longer
overlapping the interior of Q (0 unless penetrating); depth: α·|d| (nearest
double); translation: α·d (exact Fraction triple).)")
      .def_property_readonly("status", [=](const DirectionalDepthResult& r) { return status(r.status); })
      .def_property_readonly("t", [](const DirectionalDepthResult& r) { return to_fraction(r.t); })
      .def_readonly("depth", &DirectionalDepthResult::depth)
      .def_property_readonly("translation", [](const DirectionalDepthResult& r) { return to_fractions(r.translation); })
      .def_property_readonly("witness", [](const DirectionalDepthResult& r) { return WitnessPy{r.witness}; });

  py::class_<Obstacle>(m, "Obstacle", R"(Exact proximity queries between P and Q under translation.

Obstacle(p, q, method="auto") computes the configuration-space obstacle
M = P ⊕ (−Q) once (p and q: Polytope objects, file paths or catalog names).
Each query takes t, the translation of Q relative to P (Q moved by t, P
fixed; for P moved by u and Q by w, t = w − u).  The command 'minksum query'
moves P by --translate-p u and Q by --translate-q w: its answer is that of
t = w − u here, so --translate-p u alone is t = −u.  t is one translation
(a triple of exact numbers or an array of shape (3,)) or a batch of them (an
(N, 3) array, floats taken exactly, or a sequence of triples).  The queries
answer exactly:
  collide(t)               "separate", "touching" or "penetrating"
  distance(t)              separation distance, closest points
  depth(t)                 penetration depth and a minimal separating move
  directional_depth(t, d)  how far P must move along d to stop overlapping
One translation gives a result object.  A batch gives, in one call, an
array: collide an int8 array of status codes (STATUS[code]: 0 separate, 1
touching, 2 penetrating), distance, depth and directional_depth float64
arrays of the nearest doubles; with exact=True, the list of the result
objects.  Each answer of a batch is the answer of the single query.  A batch
runs with the GIL released on `threads` threads (None: one per core; one
thread per 64 translations at most), each thread a block of the poses on
an obstacle of its own (built on first use, a sum of P and −Q each, and
kept).  Successive queries start from the previous answer's witness, so a
moving query point costs little.  An Obstacle may be used from several
Python threads; its queries and batches run one at a time, with the GIL
released.)")
      .def(py::init([](py::object p, py::object q, const std::string& method) {
             const NamedOperand op = to_operand(p, "p"), oq = to_operand(q, "q");
             const Method mt = to_method(method);
             auto o = std::make_unique<Obstacle>();
             o->method = mt;
             // M's sum polled for Ctrl-C (run_interruptible: KeyboardInterrupt, no obstacle).
             std::atomic<bool> cancel{false};
             SumOptions options;
             options.cancel = &cancel;
             run_interruptible(
                 [&] {
                   o->p = resolve(op);
                   o->q = resolve(oq);
                   o->o = std::make_unique<TranslationalObstacle>(*o->p, *o->q, mt, options);
                 },
                 cancel);
             return o;
           }),
           py::arg("p"), py::arg("q"), py::arg("method") = "auto")
      .def_property_readonly("p", [](const Obstacle& o) { return std::const_pointer_cast<ConvexPolytope>(o.p); })
      .def_property_readonly("q", [](const Obstacle& o) { return std::const_pointer_cast<ConvexPolytope>(o.q); })
      .def_property_readonly(
          "obstacle", [](const Obstacle& o) { return std::make_shared<ConvexPolytope>(o.o->obstacle()); },
          "M = P ⊕ (−Q), as a Polytope.")
      .def("collide",
           query(&TranslationalObstacle::collide_point,
                 [](const std::vector<CollisionResult>& r) { return py::object(status_array(r)); }),
           py::arg("t"), py::kw_only(), py::arg("exact") = false, py::arg("threads") = py::none(),
           "Whether P and Q translated by t are separate, touching or penetrating.\n"
           "t: one translation of Q relative to P (a CollisionResult), or an (N, 3) batch: an int8 array\n"
           "of status codes (minksum.STATUS[code]: 0 separate, 1 touching, 2 penetrating; exact=True:\n"
           "the list of CollisionResult), on `threads` threads (None: one per core).")
      .def("distance",
           query(&TranslationalObstacle::distance_point,
                 [](const std::vector<DistanceResult>& r) {
                   return py::object(double_array(r, [](const DistanceResult& x) { return x.distance(); }));
                 }),
           py::arg("t"), py::kw_only(), py::arg("exact") = false, py::arg("threads") = py::none(),
           "The exact separation distance between P and Q translated by t (a DistanceResult).\n"
           "An (N, 3) batch of t: a float64 array of the distances (the nearest doubles; 0 unless\n"
           "separate); exact=True: the list of DistanceResult.")
      .def("depth",
           query(&TranslationalObstacle::penetration_depth_point,
                 [](const std::vector<DepthResult>& r) {
                   return py::object(double_array(r, [](const DepthResult& x) { return x.depth(); }));
                 }),
           py::arg("t"), py::kw_only(), py::arg("exact") = false, py::arg("threads") = py::none(),
           "The exact penetration depth of P and Q translated by t (a DepthResult).\n"
           "An (N, 3) batch of t: a float64 array of the depths (the nearest doubles; 0 unless\n"
           "penetrating); exact=True: the list of DepthResult.")
      .def(
          "directional_depth",
          [](Obstacle& o, py::object t, py::object d, bool exact, std::optional<long long> threads) -> py::object {
            const Point3 dir = to_point(d, "d", "direction");
            if (is_zero(dir)) throw py::value_error("d: the direction must not be the zero vector");
            if (is_batch(t)) {
              const std::vector<Point3> ts = to_translations(t);
              auto r = batch<DirectionalDepthResult>(o, ts, threads, [&dir](TranslationalObstacle& ob, const Point3& s) {
                return ob.directional_depth_point(s, dir);
              });
              if (exact) {
                py::list out;
                for (auto& x : r) out.append(py::cast(std::move(x)));
                return out;
              }
              return double_array(r, [](const DirectionalDepthResult& x) { return x.depth; });
            }
            const Point3 s = to_point(t, "t");
            DirectionalDepthResult r;
            {
              py::gil_scoped_release nogil;
              std::lock_guard<std::mutex> lock(o.m);
              r = o.o->directional_depth_point(s, dir);
            }
            return py::cast(std::move(r));
          },
          py::arg("t"), py::arg("d"), py::kw_only(), py::arg("exact") = false, py::arg("threads") = py::none(),
          "How far P must move along d (not normalised) to stop overlapping Q translated by t.\n"
          "An (N, 3) batch of t (one d): a float64 array of the depths α·|d|; exact=True: the list of\n"
          "DirectionalDepthResult.")
      .def("__repr__", [](const Obstacle& o) {
        const ConvexPolytope& mm = o.o->obstacle();
        return "<minksum.Obstacle: M has " + std::to_string(mm.num_vertices()) + " vertices, " +
               std::to_string(mm.num_facets()) + " facets>";
      });


  py::class_<RigidBody>(m, "RigidBody", R"(A convex polytope prepared for collision under rigid motion.

RigidBody(p) (a Polytope, a file path or a catalog name) keeps its vertex
graph, the doubles of its vertices and their enclosures, built once and
shared by every pose and thread of collide_rigid and distance_rigid.)")
      .def(py::init([](py::object p) { return RigidBody(*resolve(to_operand(p, "p"))); }), py::arg("p"))
      .def_property_readonly(
          "polytope", [](const RigidBody& b) { return std::make_shared<ConvexPolytope>(b.polytope()); })
      .def("__repr__", [](const RigidBody& b) {
        return "<minksum.RigidBody: " + std::to_string(b.polytope().num_vertices()) + " vertices>";
      });
  m.def(
      "collide_rigid",
      [](const RigidBody& a, const RigidBody& b, py::object tb, py::object rb, py::object ta, py::object ra,
         std::optional<long long> threads) {
        const RigidPoses poses(tb, rb, ta, ra, threads);
        py::array_t<std::int8_t> codes(static_cast<py::ssize_t>(poses.n));
        std::int8_t* w = codes.mutable_data();
        {
          py::gil_scoped_release nogil;
          const PoseSource source(poses);
          std::vector<RigidCollision> out(poses.n);
          collide(a, b, source.source(), out, poses.threads);
          for (std::size_t i = 0; i < poses.n; ++i) w[i] = static_cast<std::int8_t>(out[i].status);
        }
        return codes;
      },
      py::arg("a"), py::arg("b"), py::arg("t_b") = py::none(), py::arg("r_b") = py::none(),
      py::arg("t_a") = py::none(), py::arg("r_a") = py::none(), py::kw_only(), py::arg("threads") = py::none(),
      R"(Exact collision of a and b (RigidBody), each under a rotation and a translation, for N poses in one call.

b is rotated by r_b, then translated by t_b (and a by r_a, t_a).  t: an
(N, 3) or (3,) array (floats taken exactly) or None (no translation); r: an
(N, 4) or (4,) integer array of quaternions (exact rational rotations, as
'@rot:'), an (N, 3, 3) or (3, 3) float array of matrices taken exactly as
given (the answer is exact for that matrix; its determinant must be
positive), or None (no rotation).  One pose stands for all N.  Returns an
int8 array of N status codes (minksum.STATUS[code]: 0 separate, 1 touching,
2 penetrating), each certified exactly (docs/proximity.md, "Rigid motion").
Runs with the GIL released on `threads` threads (None: one per core).)");
  m.def(
      "distance_rigid",
      [](const RigidBody& a, const RigidBody& b, py::object tb, py::object rb, py::object ta, py::object ra,
         std::optional<long long> threads, bool exact) {
        const RigidPoses poses(tb, rb, ta, ra, threads);
        const std::size_t n = poses.n;
        const auto sn = static_cast<py::ssize_t>(n);
        py::array_t<std::int8_t> status(sn);
        py::array_t<double> dist(sn), lower(sn), upper(sn), point_a({sn, py::ssize_t(3)}), point_b({sn, py::ssize_t(3)});
        std::int8_t* ws = status.mutable_data();
        double *wd = dist.mutable_data(), *wl = lower.mutable_data(), *wu = upper.mutable_data();
        double *wa = point_a.mutable_data(), *wb = point_b.mutable_data();
        std::vector<RigidDistanceExact> values;
        {
          py::gil_scoped_release nogil;
          const PoseSource source(poses);
          std::vector<RigidDistance> out(n);
          distance(a, b, source.source(), out, poses.threads);
          for (std::size_t i = 0; i < n; ++i) {
            const RigidDistance& d = out[i];
            ws[i] = static_cast<std::int8_t>(d.status);
            wd[i] = d.distance, wl[i] = d.lower, wu[i] = d.upper;
            for (int k = 0; k < 3; ++k) wa[3 * i + k] = d.point_p[k], wb[3 * i + k] = d.point_q[k];
          }
          if (exact) values = batch_exact_values(a, b, source, out, poses.threads);
        }
        py::dict r;
        r["status"] = status;
        r["distance"] = dist;
        r["lower"] = lower;
        r["upper"] = upper;
        r["point_a"] = point_a;
        r["point_b"] = point_b;
        if (exact) {
          py::list sq, ea, eb;
          for (const RigidDistanceExact& v : values) {
            sq.append(to_fraction(v.squared_distance));
            ea.append(to_fractions(v.point_p));
            eb.append(to_fractions(v.point_q));
          }
          r["squared_distance"] = sq;
          r["exact_point_a"] = ea;
          r["exact_point_b"] = eb;
        }
        return r;
      },
      py::arg("a"), py::arg("b"), py::arg("t_b") = py::none(), py::arg("r_b") = py::none(),
      py::arg("t_a") = py::none(), py::arg("r_a") = py::none(), py::kw_only(), py::arg("threads") = py::none(),
      py::arg("exact") = false,
      R"(Exact separation distance of a and b (RigidBody), each under a rotation and a translation, for N poses in one call.

The poses are those of collide_rigid (b rotated by r_b then translated by
t_b, a by r_a and t_a; one pose stands for all N).  Returns a dict of numpy
arrays: status (int8 (N,), minksum.STATUS[code]), distance (float64 (N,),
0 unless separate), lower and upper (float64 (N,): lower <= the exact
distance <= upper, certified), point_a and point_b (float64 (N, 3): closest
points of placed a and placed b, a common point when they meet).
exact=True adds squared_distance (a list of N fractions.Fraction, the exact
squared distance, 0 unless separate) and exact_point_a, exact_point_b
(lists of N exact Fraction triples: closest points, or a common point when
the bodies meet, the one point_a is near).  Runs with the GIL released on
`threads` threads (None: one per core); docs/proximity.md, "Rigid motion".)");

  m.def(
      "depth_rigid",
      [](const RigidBody& a, const RigidBody& b, py::object tb, py::object rb, py::object ta, py::object ra,
         std::optional<long long> threads, bool exact) {
        const RigidPoses poses(tb, rb, ta, ra, threads);
        const std::size_t n = poses.n;
        const auto sn = static_cast<py::ssize_t>(n);
        py::array_t<std::int8_t> status(sn);
        py::array_t<double> depth(sn), lower(sn), upper(sn), direction({sn, py::ssize_t(3)});
        std::int8_t* ws = status.mutable_data();
        double *wd = depth.mutable_data(), *wl = lower.mutable_data(), *wu = upper.mutable_data();
        double* wt = direction.mutable_data();
        std::vector<RigidDepthExact> values;
        {
          py::gil_scoped_release nogil;
          const PoseSource source(poses);
          std::vector<RigidDepth> out(n);
          penetration_depth(a, b, source.source(), out, poses.threads);
          for (std::size_t i = 0; i < n; ++i) {
            const RigidDepth& d = out[i];
            ws[i] = static_cast<std::int8_t>(d.status);
            wd[i] = d.depth, wl[i] = d.lower, wu[i] = d.upper;
            for (int k = 0; k < 3; ++k) wt[3 * i + k] = d.direction[k];
          }
          if (exact) values = batch_exact_values(a, b, source, out, poses.threads);
        }
        py::dict r;
        r["status"] = status;
        r["depth"] = depth;
        r["lower"] = lower;
        r["upper"] = upper;
        r["direction"] = direction;
        if (exact) {
          py::list sq, dir;
          for (const RigidDepthExact& v : values) sq.append(to_fraction(v.squared_depth)), dir.append(to_fractions(v.direction));
          r["squared_depth"] = sq;
          r["exact_direction"] = dir;
        }
        return r;
      },
      py::arg("a"), py::arg("b"), py::arg("t_b") = py::none(), py::arg("r_b") = py::none(),
      py::arg("t_a") = py::none(), py::arg("r_a") = py::none(), py::kw_only(), py::arg("threads") = py::none(),
      py::arg("exact") = false,
      R"(Exact penetration depth of a and b (RigidBody), each under a rotation and a translation, for N poses in one call.

The poses are those of collide_rigid.  Returns a dict of numpy arrays:
status (int8 (N,), minksum.STATUS[code]), depth (float64 (N,), 0 unless
penetrating), lower and upper (float64 (N,): lower <= the exact depth <=
upper, certified), direction (float64 (N, 3): the shortest translation of
a that ends the overlap).  exact=True adds squared_depth (a list of N
fractions.Fraction) and exact_direction (a list of N Fraction triples).
Runs with the GIL released on `threads` threads (None: one per core);
docs/proximity.md, "Rigid motion".)");

  py::list names;
  for (const MethodInfo& mi : methods()) names.append(mi.name);
  m.attr("METHODS") = py::tuple(names);
  m.attr("STATUS") = py::make_tuple("separate", "touching", "penetrating");  // the codes of collide() on a batch
}
