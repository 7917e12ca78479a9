#pragma once

#include <vector>

namespace pcl_crf {

/** \brief Homogeneity, completeness and V-measure of a clustering, each in [0, 1]
 *  (Rosenberg & Hirschberg, "V-Measure: A conditional entropy-based external
 *  cluster evaluation measure", EMNLP 2007).
 */
struct VMeasure
{
  /** 1 - H(C|K) / H(C): every cluster holds items of a single class. */
  double homogeneity = 0.0;
  /** 1 - H(K|C) / H(K): every class lies in a single cluster. */
  double completeness = 0.0;
  /** weighted harmonic mean (1 + beta) h c / (beta h + c). */
  double v = 0.0;
};

/** \brief Scores a clustering K against classes C of the same n items.
 *
 *  Entropies use the natural logarithm and the contingency table of (C, K).
 *  Labels are arbitrary ints, so renaming the labels of either side leaves the
 *  result unchanged. Degenerate cases follow the paper: homogeneity is 1 when
 *  there is a single class (H(C) = 0), completeness is 1 when there is a single
 *  cluster (H(K) = 0), and V is 0 when beta h + c = 0.
 *
 *  \param[in] classes the true class of every item
 *  \param[in] clusters the cluster of every item (same length as \a classes)
 *  \param[in] beta weight of completeness against homogeneity, >= 0 (default 1:
 *             both weigh the same)
 *  \throws std::invalid_argument on empty input, different lengths or a
 *          negative or non-finite beta.
 *
 *  \code
 *  const pcl_crf::VMeasure score = pcl_crf::computeVMeasure ({0, 0, 1, 1}, {0, 0, 0, 1});
 *  // score.homogeneity ~ 0.311, score.completeness ~ 0.384, score.v ~ 0.344
 *  \endcode
 */
VMeasure
computeVMeasure (const std::vector<int>& classes, const std::vector<int>& clusters,
                 double beta = 1.0);

}  // namespace pcl_crf
