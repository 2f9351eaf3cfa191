#pragma once
// Sites split across processes (issue 17, "Scale"): a survey of hundreds of sites inverted by the ranks of an MPI
// world (ensemble::Cluster), each rank's threads (oneTBB, InversionOptions::threads) running its own sites' runs.
//
// Why sites: a site's inversion (invert_site: the simulations of its objects over the PGA x frequency grid) is the
// expensive part of a regional survey and needs nothing from any other site; the joint fit (region.hpp) then takes
// milliseconds on the gathered likelihoods. So the split is static: sites are dealt to ranks by the longest-
// processing-time rule on their object counts (a site's runs are cells x motions x objects; cells and motions are the
// survey's own), each rank builds the motion family once and inverts its sites (invert_sites), and the results are
// gathered by each rank broadcasting its packed results in turn (Cluster::broadcast; a gather to rank 0 that leaves
// every rank with the whole survey). Results are the 1-rank results exactly (each site's runs use the same motions
// and seeds whichever rank does them; doubles travel by bit pattern), except InversionResult::seconds (wall time).
#include <cstdint>
#include <vector>

#include "topple/ensemble/ensemble.hpp"
#include "topple/inversion/inversion.hpp"

namespace topple {

/// The rank (0 .. ranks - 1) that inverts each site: sites by decreasing object count (ties: survey order), each to
/// the rank with the fewest objects so far (ties: the lower rank). Deterministic; every rank computes the same.
[[nodiscard]] std::vector<int> assign_sites_to_ranks(const std::vector<Site>& sites, int ranks);

/// invert_sites with the sites split across the cluster's ranks (header). Every rank returns every site's result, in
/// the order of `sites`. An error on any rank ends every rank's call: the rank that failed rethrows its exception, the
/// others throw SolverError naming that rank.
[[nodiscard]] std::vector<InversionResult> invert_sites_distributed(const std::vector<Site>& sites,
                                                                    const InversionSettings& settings,
                                                                    const InversionOptions& options,
                                                                    ensemble::Cluster& cluster);

/// InversionResults as 64-bit words and back (the broadcast's payload): exact (doubles by bit pattern), every field.
[[nodiscard]] std::vector<std::uint64_t> pack_inversion_results(const std::vector<InversionResult>& results);
[[nodiscard]] std::vector<InversionResult> unpack_inversion_results(const std::vector<std::uint64_t>& words);

}  // namespace topple
