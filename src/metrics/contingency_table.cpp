#include <pcl_crf/metrics/contingency_table.h>

#include <stdexcept>
#include <string>

namespace pcl_crf {

ContingencyTable::ContingencyTable (const std::vector<int>& rows, const std::vector<int>& columns)
{
  if (rows.size () != columns.size ())
    throw std::invalid_argument ("[pcl_crf::ContingencyTable] " + std::to_string (rows.size ()) +
                                 " row labels but " + std::to_string (columns.size ()) +
                                 " column labels; both labellings must cover the same items");
  for (std::size_t i = 0; i < rows.size (); ++i) {
    ++cells_[{rows[i], columns[i]}];
    ++row_totals_[rows[i]];
    ++column_totals_[columns[i]];
  }
  total_ = rows.size ();
}

std::size_t
ContingencyTable::count (int row, int column) const
{
  const auto cell = cells_.find ({row, column});
  return cell == cells_.end () ? 0 : cell->second;
}

}  // namespace pcl_crf
