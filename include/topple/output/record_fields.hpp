#pragma once
// The field table of a record's metadata (ground_motion.hpp: RecordMetadata), as kIntensityFields is the table of its
// measures: `topple info --json` writes it (after "file", the path as typed, which stands for source_file) and
// Python's GroundMotion.metadata is the dict of every field. A field is added or renamed here, once.
#include <array>

#include "topple/core/field.hpp"
#include "topple/motion/ground_motion.hpp"

namespace topple {

/// format, source_file, event, station, component, azimuth_deg (null when the file does not state it), vertical,
/// units_as_read.
extern const std::array<Field<RecordMetadata>, 8> kRecordMetadataFields;

}  // namespace topple
