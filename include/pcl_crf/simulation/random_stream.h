#pragma once

#include <cstdint>
#include <random>
#include <vector>

namespace pcl_crf {
namespace simulation {

/** \brief A reproducible stream of random numbers: the same seed gives the same
 *  numbers on every platform.
 *
 *  The raw 64-bit numbers come from \c std::mt19937_64, whose output the C++
 *  standard fixes exactly; the uniform and normal draws are computed here rather
 *  than by the (implementation-defined) \c std:: distributions. Every draw
 *  consumes a fixed count of raw numbers (uniform: 1, normal: 2), so the
 *  position of a draw in the stream never depends on earlier values.
 *
 *  \code
 *  // pair 7 of seed 42, the stream reserved for the source scan's noise
 *  pcl_crf::simulation::RandomStream rng (42, 7, 3);
 *  const double noise = rng.normal (0.0, 0.01);
 *  \endcode
 */
class RandomStream
{
public:
  /** \brief A stream seeded directly with \a seed. */
  explicit RandomStream (std::uint64_t seed = 0);

  /** \brief The independent sub-stream \a purpose of item \a index of a run
   *  seeded with \a seed (see deriveSeed()).
   */
  RandomStream (std::uint64_t seed, std::uint64_t index, std::uint64_t purpose);

  /** \brief Mixes (seed, index, purpose) into one engine seed with SplitMix64, so
   *  neighbouring indices give unrelated streams.
   */
  static std::uint64_t
  deriveSeed (std::uint64_t seed, std::uint64_t index, std::uint64_t purpose);

  /** \brief The next raw 64-bit number of the engine. */
  std::uint64_t
  raw ();

  /** \brief Uniform in [0, 1) with 53 random bits. */
  double
  uniform ();

  /** \brief Uniform in [low, high). */
  double
  uniform (double low, double high);

  /** \brief Uniform integer in [low, high] (both included); low when high < low. */
  int
  uniformInt (int low, int high);

  /** \brief Standard normal N(0, 1) by the Box–Muller transform. */
  double
  normal ();

  /** \brief Normal with the given mean and standard deviation. */
  double
  normal (double mean, double stddev);

  /** \brief true with the given probability. */
  bool
  bernoulli (double probability);

  /** \brief An index drawn with probability proportional to \a weights
   *  (non-negative, not all zero).
   */
  std::size_t
  choose (const std::vector<double>& weights);

private:
  std::mt19937_64 engine_;
};

}  // namespace simulation
}  // namespace pcl_crf
