#pragma once

/** \file
 *  \brief Everything needed to score predictions against scan-pair truth.
 */

#include <pcl_crf/metrics/association_metrics.h>
#include <pcl_crf/metrics/cluster_matching.h>
#include <pcl_crf/metrics/clustering_metrics.h>
#include <pcl_crf/metrics/contingency_table.h>
#include <pcl_crf/metrics/edit_distance.h>
#include <pcl_crf/metrics/motion_error.h>
#include <pcl_crf/metrics/pair_scores.h>
#include <pcl_crf/metrics/summary.h>
#include <pcl_crf/metrics/v_measure.h>
#include <pcl_crf/metrics/v_measure_ceiling.h>
#include <pcl_crf/metrics/validate_prediction.h>
