// Messages of proto/ printed as JSON for the command line: field names as in the .proto,
// every field present, indented.
#pragma once

#include <string>

#include "google/protobuf/message.h"

namespace kerf::cli {

std::string FormatProtoJson(const google::protobuf::Message& message);

}  // namespace kerf::cli
