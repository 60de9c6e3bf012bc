// The table of per-query counters (kQueryCounters): it names every counter once, and what adds
// counters adds every row of it.
#include <bvhlab/counters.h>

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace bvhlab {
namespace {

// Counters with a distinct value in every counter of the table, from `first` on.
QueryCounters distinctCounters(uint64_t first) {
    QueryCounters c;
    for (const QueryCounter& row : kQueryCounters) c.*row.count = first++;
    return c;
}

TEST(QueryCounters, AddWorkAddsEveryCounterOfTheTableButNotTheQueries) {
    QueryCounters sum = distinctCounters(1);
    sum.queries = 5;
    sum.counting = false;
    const QueryCounters work = distinctCounters(100);
    sum.addWork(work);
    const QueryCounters before = distinctCounters(1);
    for (const QueryCounter& row : kQueryCounters)
        EXPECT_EQ(sum.*row.count, before.*row.count + work.*row.count) << row.key;
    EXPECT_EQ(sum.queries, 5u);
    EXPECT_FALSE(sum.counting);
}

TEST(QueryCounters, PlusAddsTheQueriesAndEveryCounterOfTheTable) {
    QueryCounters sum = distinctCounters(1), other = distinctCounters(1);
    sum.queries = 2;
    other.queries = 3;
    sum += other;
    EXPECT_EQ(sum.queries, 5u);
    uint64_t first = 1;
    for (const QueryCounter& row : kQueryCounters) EXPECT_EQ(sum.*row.count, 2 * first++) << row.key;
}

TEST(QueryCounters, EveryCounterHasItsOwnSlotKeyAndColumn) {
    std::set<std::string> keys, columns;
    for (size_t i = 0; i < std::size(kQueryCounters); ++i) {
        const QueryCounter& row = kQueryCounters[i];
        EXPECT_TRUE(keys.insert(row.key).second) << row.key;
        if (row.column) {
            EXPECT_TRUE(columns.insert(row.column).second) << row.column;
        }
        EXPECT_NE(std::string(row.meaning), "") << row.key;
        EXPECT_NE(row.count, &QueryCounters::queries) << row.key;
        for (size_t j = 0; j < i; ++j) EXPECT_NE(row.count, kQueryCounters[j].count) << row.key;
    }
}

}  // namespace
}  // namespace bvhlab
