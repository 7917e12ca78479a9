#pragma once

#include <pcl_crf/evaluation/method.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace pcl_crf {

/** \brief Version written in the first line of a composite model file. */
constexpr int kCompositeModelVersion = 1;

/** \brief Writes the model of a method made of parts (e.g. CRF-Matching then
 *  CRF-Clustering) as one versioned text: a header, then each part's own model text
 *  (EvaluationMethod::writeModel) between "part NAME" and "end_part NAME".
 *
 *  \code{.unparsed}
 *  pcl_crf_composite_model 1
 *  method crf-m
 *  parts crf-matching crf-clustering
 *  part crf-matching
 *  pcl_crf_crf_matching_model 1
 *  ...
 *  end_part crf-matching
 *  part crf-clustering
 *  pcl_crf_crf_clustering_model 1
 *  ...
 *  end_part crf-clustering
 *  \endcode
 *  \param[out] os the text
 *  \param[in] method the composite method's name
 *  \param[in] parts its learned parts, in order (their names must be single words)
 *  \throws std::runtime_error when a part cannot write its model (e.g. not trained)
 */
void
writeCompositeModel (std::ostream& os, const std::string& method, const std::vector<const EvaluationMethod*>& parts);

/** \brief Reads text written by writeCompositeModel into \a parts (each part's
 *  readModel sees its own text, with the line numbers of the whole file).
 *  \param[in] is the text
 *  \param[in] where the file name, for messages
 *  \param[in] method the expected method name
 *  \param[in] parts the expected parts, in order
 *  \throws std::runtime_error "<where>: line <n>: <problem>" for a wrong header,
 *  version, method or part list, a missing "end_part" (truncated file), text after the
 *  last part, or a part's own error (naming the file and the part)
 */
void
readCompositeModel (std::istream& is, const std::string& where, const std::string& method,
                    const std::vector<EvaluationMethod*>& parts);

}  // namespace pcl_crf
