// libsph_catalyst.so: the ParaView Catalyst adaptor of `sph run --catalyst
// SCRIPT.py` (the C interface is sph/io/catalyst_plugin.h; sph loads this
// library with dlopen only then, src/catalyst.cpp).
//
// It is the legacy ("Catalyst 1") adaptor of ParaView 5.11: a
// vtkCPProcessor with one pipeline, a vtkCPDataDescription with one input
// "input" holding the particles as the vtkPolyData that the .vtp writer
// writes (snapshotPolyData), time and step, and a legacy pipeline script
// with RequestDataDescription(datadescription) and
// DoCoProcessing(datadescription), as ParaView's "Export Catalyst Script"
// wrote them and as Kitware's Catalyst 1 examples use them.
//
// The script is loaded and called by ScriptPipeline below, not by
// vtkCPPythonScriptPipeline: that one runs the script with
// PyRun_SimpleString and returns success whatever happens, so a script with
// a syntax error, without the two functions, or raising while it loads
// would only print a traceback and the run would go on without its
// pictures. Here each of those is one line that sph reports before the run.
#include "sph/io/catalyst_plugin.h"

#include <vtkPython.h>  // first: Python.h

#include <vtkCPDataDescription.h>
#include <vtkCPInputDataDescription.h>
#include <vtkCPPipeline.h>
#include <vtkCPProcessor.h>
#include <vtkFieldData.h>
#include <vtkMPI.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkPythonInterpreter.h>
#include <vtkPythonUtil.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include <cstdio>
#include <string>

namespace {

// Python side: loading the script as a module and calling it, each error
// turned into one line (the exception and the script's line).
const char* kHelper = R"PY(
import ast, os, sys, traceback, types
sys.dont_write_bytecode = True
from paraview.modules import vtkPVCatalyst  # the wrapper of vtkCPDataDescription

NEEDED = ("RequestDataDescription", "DoCoProcessing")

def one_line(error, script):
    if isinstance(error, SystemExit):  # the script's own message
        return " ".join(str(error.code).split())
    text = "%s: %s" % (type(error).__name__, error)
    lines = [f.lineno for f in traceback.extract_tb(error.__traceback__) if f.filename == script]
    where = " (line %d)" % lines[-1] if lines else ""
    return " ".join(text.split()) + where

def load(script):
    try:
        with open(script, encoding="utf-8") as fh:
            source = fh.read()
    except (OSError, UnicodeDecodeError) as e:
        return None, "cannot be read: %s" % e
    try:
        tree = ast.parse(source, script)
    except (SyntaxError, ValueError) as e:
        return None, "has a Python syntax error at line %s: %s" % (getattr(e, "lineno", "?"), getattr(e, "msg", e))
    defined = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            defined.add(node.name)
        elif isinstance(node, ast.Assign):
            defined.update(t.id for t in node.targets if isinstance(t, ast.Name))
    missing = [f for f in NEEDED if f not in defined]
    if missing:
        return None, ("is not a Catalyst script: it defines no %s (a legacy Catalyst pipeline script "
                      "defines RequestDataDescription(datadescription) and DoCoProcessing(datadescription))"
                      % " and no ".join(missing))
    module = types.ModuleType("sph_catalyst_script")
    module.__file__ = script
    sys.path.insert(0, os.path.dirname(script))
    try:
        exec(compile(tree, script, "exec"), module.__dict__)
    except BaseException as e:
        return None, "failed to load: " + one_line(e, script)
    for f in NEEDED:
        if not callable(getattr(module, f, None)):
            return None, "is not a Catalyst script: %s is not a function" % f
    return module, ""

def call(module, name, description):
    try:
        getattr(module, name)(description)
        return ""
    except BaseException as e:
        return "%s: %s" % (name, one_line(e, module.__file__))

def finalize(module):
    if not callable(getattr(module, "Finalize", None)):
        return ""
    try:
        module.Finalize()
        return ""
    except BaseException as e:
        return "Finalize: " + one_line(e, module.__file__)
)PY";

void setError(char* error, std::size_t size, const std::string& text) {
  if (error && size) std::snprintf(error, size, "%s", text.c_str());
}

// The text of the pending Python exception, cleared.
std::string pythonError() {
  PyObject *type = nullptr, *value = nullptr, *trace = nullptr;
  PyErr_Fetch(&type, &value, &trace);
  std::string text = "Python error";
  if (value) {
    if (PyObject* s = PyObject_Str(value)) {
      if (const char* c = PyUnicode_AsUTF8(s)) text = c;
      Py_DECREF(s);
    }
  }
  Py_XDECREF(type);
  Py_XDECREF(value);
  Py_XDECREF(trace);
  PyErr_Clear();
  return text;
}

// The GIL for one scope (Catalyst may have released it).
struct Gil {
  PyGILState_STATE state = PyGILState_Ensure();
  ~Gil() { PyGILState_Release(state); }
};

// The script as a Catalyst pipeline: its RequestDataDescription and
// DoCoProcessing, called through the helper so that errors come back.
class ScriptPipeline : public vtkCPPipeline {
 public:
  static ScriptPipeline* New();
  vtkTypeMacro(ScriptPipeline, vtkCPPipeline)

  // "" or why the script cannot be used.
  std::string load(const std::string& script) {
    Gil gil;
    helper_ = PyDict_New();
    PyDict_SetItemString(helper_, "__builtins__", PyEval_GetBuiltins());
    PyObject* ran = PyRun_String(kHelper, Py_file_input, helper_, helper_);
    if (!ran) return "ParaView's Python modules cannot be loaded: " + pythonError();
    Py_DECREF(ran);
    PyObject* result = PyObject_CallFunction(PyDict_GetItemString(helper_, "load"), "s", script.c_str());
    if (!result) return "failed to load: " + pythonError();
    PyObject* module = PyTuple_GetItem(result, 0);
    const char* message = PyUnicode_AsUTF8(PyTuple_GetItem(result, 1));
    const std::string why = message ? message : "";
    if (why.empty()) {
      module_ = module;
      Py_INCREF(module_);
    }
    Py_DECREF(result);
    return why;
  }

  int RequestDataDescription(vtkCPDataDescription* description) override {
    if (!call("RequestDataDescription", description)) return 0;
    return description->GetIfAnyGridNecessary() ? 1 : 0;
  }

  int CoProcess(vtkCPDataDescription* description) override { return call("DoCoProcessing", description) ? 1 : 0; }

  int Finalize() override {
    if (!module_) return 1;
    Gil gil;
    PyObject* r = PyObject_CallFunction(PyDict_GetItemString(helper_, "finalize"), "O", module_);
    if (!r) error_ = pythonError();
    else {
      const char* text = PyUnicode_AsUTF8(r);
      error_ = text ? text : "";
      Py_DECREF(r);
    }
    return error_.empty() ? 1 : 0;
  }

  const std::string& error() const { return error_; }

 protected:
  ScriptPipeline() = default;
  ~ScriptPipeline() override {
    if (!Py_IsInitialized()) return;
    Gil gil;
    Py_XDECREF(module_);
    Py_XDECREF(helper_);
  }

 private:
  bool call(const char* name, vtkCPDataDescription* description) {
    Gil gil;
    PyObject* wrapped = vtkPythonUtil::GetObjectFromPointer(description);
    if (!wrapped) {
      error_ = std::string(name) + ": " + pythonError();
      return false;
    }
    PyObject* r = PyObject_CallFunction(PyDict_GetItemString(helper_, "call"), "OsO", module_, name, wrapped);
    Py_DECREF(wrapped);
    if (!r) {
      error_ = std::string(name) + ": " + pythonError();
      return false;
    }
    const char* text = PyUnicode_AsUTF8(r);
    error_ = text ? text : "";
    Py_DECREF(r);
    return error_.empty();
  }

  PyObject* helper_ = nullptr;  // the helper's globals
  PyObject* module_ = nullptr;  // the script
  std::string error_;
};
vtkStandardNewMacro(ScriptPipeline);

struct Session {
  vtkSmartPointer<vtkCPProcessor> processor;
  vtkSmartPointer<ScriptPipeline> pipeline;
  vtkSmartPointer<vtkCPDataDescription> description;  // of the last request
  vtkSmartPointer<vtkFieldData> userData;
};
Session* session = nullptr;

vtkSmartPointer<vtkStringArray> stringValue(const char* name, const char* value) {
  auto a = vtkSmartPointer<vtkStringArray>::New();
  a->SetName(name);
  a->InsertNextValue(value);
  return a;
}

}  // namespace

extern "C" {

int sph_catalyst_abi(void) { return SPH_CATALYST_ABI; }

int sph_catalyst_initialize(const char* script, const char* run_folder, const char* run_name, void* mpi_comm,
                            char* error, size_t size) {
  if (session) {
    setError(error, size, "Catalyst is already running in this process");
    return -1;
  }
  auto s = new Session;
  s->processor = vtkSmartPointer<vtkCPProcessor>::New();
  vtkMPICommunicatorOpaqueComm ranks(static_cast<MPI_Comm*>(mpi_comm));
  if (!(mpi_comm ? s->processor->Initialize(ranks) : s->processor->Initialize())) {
    delete s;
    setError(error, size, "ParaView's Catalyst could not be initialised");
    return -1;
  }
  if (!vtkPythonInterpreter::IsInitialized()) vtkPythonInterpreter::Initialize(0);  // 0: keep sph's signal handlers
  s->pipeline = vtkSmartPointer<ScriptPipeline>::New();
  const std::string why = s->pipeline->load(script);
  if (!why.empty()) {
    s->pipeline = nullptr;
    s->processor->Finalize();
    delete s;
    setError(error, size, why);
    return -1;
  }
  s->processor->AddPipeline(s->pipeline);
  s->userData = vtkSmartPointer<vtkFieldData>::New();
  s->userData->AddArray(stringValue("run_folder", run_folder));
  s->userData->AddArray(stringValue("run_name", run_name));
  session = s;
  return 0;
}

int sph_catalyst_request(double time, long step, int last, char* error, size_t size) {
  if (!session) {
    setError(error, size, "Catalyst is not initialised");
    return -1;
  }
  auto d = vtkSmartPointer<vtkCPDataDescription>::New();
  d->AddInput("input");
  d->SetTimeData(time, static_cast<vtkIdType>(step));
  d->SetForceOutput(last != 0);
  d->SetUserData(session->userData);
  session->description = d;
  const int wanted = session->processor->RequestDataDescription(d);
  if (!session->pipeline->error().empty()) {
    setError(error, size, session->pipeline->error());
    return -1;
  }
  return wanted ? 1 : 0;
}

int sph_catalyst_coprocess(void* polydata, char* error, size_t size) {
  if (!session || !session->description) {
    setError(error, size, "Catalyst: no request before the particles");
    return -1;
  }
  session->description->GetInputDescriptionByName("input")->SetGrid(static_cast<vtkPolyData*>(polydata));
  session->processor->CoProcess(session->description);
  session->description = nullptr;  // the grid is the caller's: not kept
  if (!session->pipeline->error().empty()) {
    setError(error, size, session->pipeline->error());
    return -1;
  }
  return 0;
}

void sph_catalyst_finalize(void) {
  if (!session) return;
  session->processor->Finalize();  // calls the pipeline's Finalize
  delete session;
  session = nullptr;
}

}  // extern "C"
