#include <pcl_crf/crf/lbfgs_minimizer.h>

#include <lbfgs.h>

#include <cmath>
#include <deque>
#include <exception>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

/** Everything the C callbacks need, passed through liblbfgs' instance pointer. */
struct CallbackData
{
  const Objective* objective = nullptr;
  const LbfgsOptions* options = nullptr;
  Eigen::VectorXd x, gradient;
  std::exception_ptr error;
  bool first_evaluation = true;
  double value = 0.0;  // objective at the last accepted point
  int iterations = 0;
  bool stopped_by_delta = false;
  std::deque<double> history;  // objective values of the last iterations
};

lbfgsfloatval_t
evaluate (void* instance, const lbfgsfloatval_t* x, lbfgsfloatval_t* g, const int n, const lbfgsfloatval_t)
{
  auto& data = *static_cast<CallbackData*> (instance);
  Eigen::Map<Eigen::VectorXd> (g, n).setZero ();
  if (data.error)
    return std::numeric_limits<double>::quiet_NaN ();
  try
  {
    data.x = Eigen::Map<const Eigen::VectorXd> (x, n);
    const double f = (*data.objective) (data.x, data.gradient);
    if (data.gradient.size () != n)
      throw std::invalid_argument ("[pcl_crf::crf::minimizeLbfgs] the objective returned a gradient of size " +
                                   std::to_string (data.gradient.size ()) + ", expected " + std::to_string (n));
    if (std::isnan (f) || data.gradient.hasNaN ())  // the line search cannot compare NaN: it reported convergence
      throw std::invalid_argument ("[pcl_crf::crf::minimizeLbfgs] the objective returned a NaN value or gradient");
    Eigen::Map<Eigen::VectorXd> (g, n) = data.gradient;
    if (data.first_evaluation)
      data.value = f;
    data.first_evaluation = false;
    return f;
  }
  catch (...)
  {
    data.error = std::current_exception ();  // C code must not unwind: store and cancel
    return std::numeric_limits<double>::quiet_NaN ();
  }
}

/** Decrease test (f_{k−past} − f_k) / |f_k| < delta, on the absolute value of f. */
bool
decreaseTestMet (CallbackData& data, double f)
{
  const LbfgsOptions& options = *data.options;
  if (options.past <= 0)
    return false;
  data.history.push_back (f);
  if (static_cast<int> (data.history.size ()) <= options.past)
    return false;
  const double past = data.history.front ();
  data.history.pop_front ();
  return f != 0.0 && (past - f) / std::abs (f) < options.delta;
}

int
progress (void* instance, const lbfgsfloatval_t*, const lbfgsfloatval_t*, const lbfgsfloatval_t fx,
          const lbfgsfloatval_t, const lbfgsfloatval_t, const lbfgsfloatval_t, int, int k, int)
{
  auto& data = *static_cast<CallbackData*> (instance);
  data.value = fx;
  data.iterations = k;
  if (data.error)
    return 1;
  data.stopped_by_delta = decreaseTestMet (data, fx);
  return data.stopped_by_delta ? 1 : 0;
}

std::string
statusText (int code)
{
  switch (code)
  {
    case LBFGS_SUCCESS: return "converged: gradient test met";
    case LBFGS_STOP: return "converged: decrease test met";
    case LBFGS_ALREADY_MINIMIZED: return "converged: the initial point already minimises";
    case LBFGSERR_CANCELED: return "canceled";
    case LBFGSERR_MAXIMUMITERATION: return "maximum number of iterations reached";
    case LBFGSERR_MAXIMUMLINESEARCH: return "line search: maximum number of evaluations reached";
    case LBFGSERR_ROUNDING_ERROR: return "line search: rounding error, no step satisfies the conditions";
    case LBFGSERR_MINIMUMSTEP: return "line search: step below the minimum";
    case LBFGSERR_MAXIMUMSTEP: return "line search: step above the maximum";
    case LBFGSERR_WIDTHTOOSMALL: return "line search: interval of uncertainty too small";
    case LBFGSERR_INCREASEGRADIENT: return "the search direction increases the objective";
    case LBFGSERR_OUTOFINTERVAL: return "line search: step out of the interval of uncertainty";
    case LBFGSERR_INCORRECT_TMINMAX: return "line search: interval of uncertainty too small or logic error";
    case LBFGSERR_INVALIDPARAMETERS: return "line search: negative step";
    case LBFGSERR_OUTOFMEMORY: return "out of memory";
    default: return "liblbfgs error code " + std::to_string (code);
  }
}

void
validateInput (const Eigen::VectorXd& x0, const LbfgsOptions& options)
{
  const std::string where = "[pcl_crf::crf::minimizeLbfgs] ";
  if (x0.size () == 0)
    throw std::invalid_argument (where + "x0 is empty");
  if (!x0.allFinite ())
    throw std::invalid_argument (where + "x0 has a NaN or infinite entry");
  if (options.max_iterations < 0 || options.past < 0 || !(options.epsilon >= 0.0) || !(options.delta >= 0.0))
    throw std::invalid_argument (where + "options must be non-negative");
}

}  // namespace

LbfgsResult
minimizeLbfgs (const Objective& objective, const Eigen::VectorXd& x0, const LbfgsOptions& options)
{
  if (!objective)
    throw std::invalid_argument ("[pcl_crf::crf::minimizeLbfgs] no objective given");
  validateInput (x0, options);
  const int n = static_cast<int> (x0.size ());
  std::unique_ptr<lbfgsfloatval_t, void (*) (lbfgsfloatval_t*)> x (lbfgs_malloc (n), lbfgs_free);
  if (!x)
    throw std::bad_alloc ();
  Eigen::Map<Eigen::VectorXd> (x.get (), n) = x0;

  lbfgs_parameter_t parameters;
  lbfgs_parameter_init (&parameters);
  parameters.max_iterations = options.max_iterations;
  parameters.epsilon = options.epsilon;
  parameters.past = 0;  // the decrease test runs in progress () instead

  CallbackData data;
  data.objective = &objective;
  data.options = &options;
  data.gradient = Eigen::VectorXd::Zero (n);
  const int code = lbfgs (n, x.get (), nullptr, evaluate, progress, &data, &parameters);
  if (data.error)
    std::rethrow_exception (data.error);

  LbfgsResult result;
  result.x = Eigen::Map<const Eigen::VectorXd> (x.get (), n);
  result.value = data.value;
  result.iterations = data.iterations;
  result.converged = code == LBFGS_SUCCESS || code == LBFGS_STOP || code == LBFGS_ALREADY_MINIMIZED ||
                     (code == LBFGSERR_CANCELED && data.stopped_by_delta);
  result.status = data.stopped_by_delta ? "converged: decrease test met" : statusText (code);
  return result;
}

}  // namespace crf
}  // namespace pcl_crf

