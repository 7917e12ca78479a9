#pragma once

#include <cstddef>
#include <map>
#include <utility>
#include <vector>

namespace pcl_crf {

/** \brief Joint counts of two labellings of the same n items.
 *
 *  Cell (r, c) counts the items labelled r by the first labelling (the rows)
 *  and c by the second (the columns). Labels are arbitrary ints; only labels
 *  that occur get a row or a column, and only non-zero cells are stored.
 *
 *  \code
 *  const pcl_crf::ContingencyTable table ({0, 0, 1, 1}, {0, 0, 0, 1});
 *  table.count (1, 0);        // 1
 *  table.rowTotals ().at (0);  // 2
 *  \endcode
 */
class ContingencyTable
{
public:
  using Cell = std::pair<int, int>;

  /** \brief Counts the pairs (rows[i], columns[i]).
   *  \throws std::invalid_argument when the two labellings differ in length.
   */
  ContingencyTable (const std::vector<int>& rows, const std::vector<int>& columns);

  /** \brief Number of items n. */
  std::size_t
  total () const { return total_; }

  /** \brief Non-zero cells, ordered by (row, column). */
  const std::map<Cell, std::size_t>&
  cells () const { return cells_; }

  /** \brief Items per row label. */
  const std::map<int, std::size_t>&
  rowTotals () const { return row_totals_; }

  /** \brief Items per column label. */
  const std::map<int, std::size_t>&
  columnTotals () const { return column_totals_; }

  /** \brief Items labelled \a row and \a column (0 when none). */
  std::size_t
  count (int row, int column) const;

private:
  std::size_t total_ = 0;
  std::map<Cell, std::size_t> cells_;
  std::map<int, std::size_t> row_totals_;
  std::map<int, std::size_t> column_totals_;
};

}  // namespace pcl_crf
