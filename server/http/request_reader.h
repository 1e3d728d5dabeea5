#pragma once
// The body of an API request, read from what httplib parsed, in the one neutral form every route
// validates (http/api_request.h). Kept apart from the routes so that the fuzz target for whole
// requests (tests/fuzz/targets/http_request.cpp) calls exactly these.
#include <httplib.h>

#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "http/api_request.h"

namespace shadelab::http {

// The request in neutral form, whichever encoding the client used: a JSON object body,
// multipart/form-data (text parts become fields, file parts files), a urlencoded form or a GET
// query. One reader for every route, so every route answers a bad body in the same words.
Expected<RawRequest> read_request(const httplib::Request& req);

// POST /api/scene's body: a JSON scene, or multipart with the scene in the part "scene" and
// mesh files in parts the objects name.
struct SceneUpload {
  nlohmann::json scene;
  std::map<std::string, UploadedFile> files;
};
Expected<SceneUpload> read_scene(const httplib::Request& req);

}  // namespace shadelab::http
