#include <pcl_crf/simulation/random_stream.h>

#include <algorithm>
#include <cmath>

namespace pcl_crf {
namespace simulation {
namespace {

/** SplitMix64 finaliser (Steele, Lea, Flood 2014): a bijective 64-bit mixer. */
std::uint64_t
splitMix64 (std::uint64_t x)
{
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

constexpr double kTwoPi = 6.283185307179586476925286766559;

}  // namespace

RandomStream::RandomStream (std::uint64_t seed) : engine_ (seed) {}

RandomStream::RandomStream (std::uint64_t seed, std::uint64_t index, std::uint64_t purpose)
: engine_ (deriveSeed (seed, index, purpose))
{}

std::uint64_t
RandomStream::deriveSeed (std::uint64_t seed, std::uint64_t index, std::uint64_t purpose)
{
  return splitMix64 (splitMix64 (splitMix64 (seed) ^ index) ^ purpose);
}

std::uint64_t
RandomStream::raw ()
{
  return engine_ ();
}

double
RandomStream::uniform ()
{
  // The top 53 bits scaled by 2^-53: exactly representable, in [0, 1).
  return static_cast<double> (engine_ () >> 11) * 0x1.0p-53;
}

double
RandomStream::uniform (double low, double high)
{
  return low + (high - low) * uniform ();
}

int
RandomStream::uniformInt (int low, int high)
{
  const double u = uniform ();
  if (high <= low)
    return low;
  const double span = static_cast<double> (high) - static_cast<double> (low) + 1.0;
  const int k = static_cast<int> (std::floor (u * span));
  return std::min (high, low + k);
}

double
RandomStream::normal ()
{
  // Box–Muller: u1 in (0, 1] keeps the logarithm finite.
  const double u1 = 1.0 - uniform ();
  const double u2 = uniform ();
  return std::sqrt (-2.0 * std::log (u1)) * std::cos (kTwoPi * u2);
}

double
RandomStream::normal (double mean, double stddev)
{
  return mean + stddev * normal ();
}

bool
RandomStream::bernoulli (double probability)
{
  return uniform () < probability;
}

std::size_t
RandomStream::choose (const std::vector<double>& weights)
{
  double total = 0.0;
  for (double w : weights)
    total += std::max (0.0, w);
  const double u = uniform () * total;
  double cumulative = 0.0;
  for (std::size_t k = 0; k < weights.size (); ++k) {
    cumulative += std::max (0.0, weights[k]);
    if (u < cumulative)
      return k;
  }
  // Only reached through rounding at the top end: the last positive weight.
  for (std::size_t k = weights.size (); k-- > 0;)
    if (weights[k] > 0.0)
      return k;
  return 0;
}

}  // namespace simulation
}  // namespace pcl_crf
