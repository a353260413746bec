// How many YAML documents a text holds, found from yaml-cpp's parse events without building nodes.
//
// It exists because YAML::LoadAll cannot be trusted with every text: yaml-cpp 0.7 (Debian 12) does
// not consume a flow-entry token (`,`) where a document's node is expected, so LoadAll returns an
// endless run of empty documents at that place (a file holding only `,`, or `"x",`, never returns
// and grows without bound). A document that begins where the one before it began made no progress;
// the scan stops there and says where.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <optional>
#include <string>

namespace fldsim {

struct YamlDocumentScan {
  std::size_t documents = 0;                  // counted up to kYamlDocumentsScanned
  std::optional<YAML::Mark> second_document;  // the second document's first node
  std::optional<YAML::Mark> stalled_at;       // where the parser stopped making progress
};

// Enough to refuse a second document and to see whether the second one is a stall.
inline constexpr std::size_t kYamlDocumentsScanned = 3;

// Throws YAML::Exception on a syntax error, as YAML::LoadAll would.
YamlDocumentScan scan_yaml_documents(const std::string& text);

}  // namespace fldsim
