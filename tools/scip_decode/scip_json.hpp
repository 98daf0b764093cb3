// One SCIP reply as one JSON line (for slamer-scip-decode): echo, status,
// checksum_ok, key/values of VV/PP/II, timestamp/ranges/intensities of scans.
#pragma once

#include <string>

#include "drivers/urg/scip_reply.hpp"

namespace slamer::urg {

std::string reply_to_json(const Reply& reply);

}  // namespace slamer::urg
