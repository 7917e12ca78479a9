#pragma once

#include <pcl_crf/evaluation/method.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/joint/joint_learning.h>

#include <memory>

namespace pcl_crf {

/** \brief The joint model (joint::estimateJoint) as an evaluation method named "joint":
 *  learned (joint::trainJointModel; saveModel / loadModel use the joint model file).
 *
 *  Its Prediction: source_match = the MAP associations; source_cluster = the MAP
 *  clusters, with the points of the outlier cluster given the cluster of their nearest
 *  clustered neighbour in the same distance segment (as CRF-M does for points without
 *  an association, so both are scored alike); the clusters' motions; the static
 *  cluster nearest to the odometry; T_source_target = the sensor's motion.
 *
 *  \code
 *  auto joint = pcl_crf::makeJointMethod ();
 *  joint->loadModel ("data/models/joint.model");
 *  const pcl_crf::Prediction prediction = joint->predict (pair);
 *  \endcode
 */
std::unique_ptr<EvaluationMethod>
makeJointMethod (const joint::JointParameters& parameters = {}, const joint::JointLearningOptions& learning = {});

}  // namespace pcl_crf
