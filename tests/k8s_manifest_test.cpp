// deploy/k8s/ against the binary it deploys: every flag and environment variable a container
// passes is one `shadelab <command> --help` lists, the ports and probe paths are the ones the
// server answers (it is started with the manifest's own flags), the objects point at each other,
// and the ingress sets the limits of the local cluster's nginx.
#include <gtest/gtest.h>
#include <httplib.h>
#include <yaml-cpp/yaml.h>

#include "support/files.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <thread>

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const fs::path kSource = SHADELAB_SOURCE_DIR;

struct Manifest {
  std::string file;
  YAML::Node doc;
  std::string kind() const { return doc["kind"].as<std::string>(); }
  std::string name() const { return doc["metadata"]["name"].as<std::string>(); }
};

std::vector<Manifest> manifests() {
  std::vector<Manifest> out;
  for (const auto& f : fs::recursive_directory_iterator(kSource / "deploy" / "k8s"))
    if (f.path().extension() == ".yaml")
      for (const auto& doc : YAML::LoadAllFromFile(f.path().string()))
        if (doc.IsMap()) out.push_back({fs::relative(f.path(), kSource).string(), doc});
  return out;
}

std::vector<Manifest> of_kind(const std::string& kind) {
  std::vector<Manifest> out;
  for (auto& m : manifests())
    if (m.kind() == kind) out.push_back(m);
  return out;
}

using shadelab::testkit::read_text;

std::string run_output(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  pclose(pipe);
  return out;
}

std::set<std::string> matches(const std::string& text, const std::string& pattern) {
  std::set<std::string> out;
  const std::regex re(pattern);
  for (std::sregex_iterator it(text.begin(), text.end(), re), end; it != end; ++it) out.insert((*it)[1]);
  return out;
}

// A ShadeLab container: its command (args[0]), flags as written, and where it was found.
struct Container {
  std::string where;
  YAML::Node spec;
  std::string command() const { return spec["args"][0].as<std::string>(); }
  std::vector<std::string> args() const { return spec["args"].as<std::vector<std::string>>(); }
  std::string flag(const std::string& name) const {
    for (const auto& a : args())
      if (a.starts_with(name + "=")) return a.substr(name.size() + 1);
    return "";
  }
};

std::vector<Container> shadelab_containers() {
  std::vector<Container> out;
  for (const auto& m : manifests()) {
    if (m.kind() != "Deployment" && m.kind() != "Job") continue;
    for (const auto& c : m.doc["spec"]["template"]["spec"]["containers"])
      if (c["image"].as<std::string>().starts_with("shadelab")) out.push_back({m.file + " " + m.name(), c});
  }
  return out;
}

bool labels_match(const YAML::Node& selector, const YAML::Node& labels) {
  for (const auto& kv : selector)
    if (!labels[kv.first.as<std::string>()] || labels[kv.first.as<std::string>()].as<std::string>() != kv.second.as<std::string>()) return false;
  return selector.size() > 0;
}

TEST(K8sManifests, EveryDocumentIsAnObjectWithKindAndName) {
  const auto all = manifests();
  std::set<std::string> kinds;
  for (const auto& m : all) {
    EXPECT_TRUE(m.doc["apiVersion"].IsScalar()) << m.file;
    kinds.insert(m.kind());
    EXPECT_FALSE(m.name().empty()) << m.file;
  }
  for (const char* k : {"Deployment", "Service", "Ingress", "HorizontalPodAutoscaler", "PodDisruptionBudget", "ConfigMap", "Job"})
    EXPECT_TRUE(kinds.contains(k)) << "no " << k << " in deploy/k8s";
}

TEST(K8sManifests, ContainersPassOnlyFlagsAndVariablesTheBinaryKnows) {
  const auto containers = shadelab_containers();
  ASSERT_GE(containers.size(), 3u);  // the CPU and GPU replicas, the grading job
  for (const auto& c : containers) {
    const std::string help = run_output(std::string(SHADELAB_CLI) + " " + c.command() + " --help 2>&1");
    const auto flags = matches(help, R"((--[a-z0-9-]+))");
    const auto variables = matches(help, R"(Env:(SHADELAB_[A-Z0-9_]+))");
    ASSERT_FALSE(flags.empty()) << c.where << ": `" << c.command() << "` is not a command";
    for (const auto& a : c.args())
      if (a.starts_with("--")) {
        EXPECT_TRUE(flags.contains(a.substr(0, a.find('=')))) << c.where << ": " << a;
      }
    for (const auto& e : c.spec["env"]) {
      const std::string name = e["name"].as<std::string>();
      if (name.starts_with("SHADELAB_")) {
        EXPECT_TRUE(variables.contains(name)) << c.where << ": " << name;
      }
    }
    if (c.command() == "serve") {
      EXPECT_TRUE(c.spec["resources"]["requests"]["cpu"]) << c.where << ": no CPU request";
      EXPECT_TRUE(c.spec["resources"]["limits"]["memory"]) << c.where << ": no memory limit";
    }
  }
}

// The server, started with a serve container's own flags (on loopback, any port, one worker).
class ManifestServer {
 public:
  explicit ManifestServer(const Container& c) {
    std::vector<std::string> args = {SHADELAB_CLI};
    for (const auto& a : c.args())
      if (!a.starts_with("--host=") && !a.starts_with("--port=") && !a.starts_with("--workers=")) args.push_back(a);
    for (const char* a : {"--host=127.0.0.1", "--port=0", "--workers=1"}) args.emplace_back(a);
    int out[2];
    EXPECT_EQ(::pipe(out), 0);
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out[1], 2);
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(out[1]);
    std::string said;
    char buf[256];
    // Until the whole line that names the port (or the end: the server stopped, and said why).
    const std::regex serving("serving on http://[0-9.]+:([0-9]+) .*\n");
    std::smatch m;
    for (ssize_t n; !std::regex_search(said, m, serving) && (n = ::read(out[0], buf, sizeof buf)) > 0;) said.append(buf, n);
    ::close(out[0]);
    if (std::regex_search(said, m, serving)) port_ = std::stoi(m[1]);
    said_ = said;
  }
  ~ManifestServer() {
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
  }
  int port() const { return port_; }
  const std::string& said() const { return said_; }

 private:
  pid_t pid_ = 0;
  int port_ = 0;
  std::string said_;
};

int answer(int port, const std::string& path) {
  httplib::Client client("127.0.0.1", port);
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {  // readiness waits for the render workers
    if (auto res = client.Get(path)) status = res->status;
    if (status == 200) break;
    std::this_thread::sleep_for(100ms);
  }
  return status;
}

TEST(K8sManifests, ProbesAndPortsAreTheServersOwn) {
  int servers = 0;
  for (const auto& c : shadelab_containers()) {
    if (c.command() != "serve") continue;
    ++servers;
    int http_port = 0;
    for (const auto& p : c.spec["ports"])
      if (p["name"].as<std::string>() == "http") http_port = p["containerPort"].as<int>();
    EXPECT_EQ(std::to_string(http_port), c.flag("--port")) << c.where << ": the container port is not the one it listens on";
    EXPECT_EQ(c.flag("--host"), "0.0.0.0") << c.where << ": a pod must listen beyond loopback";
    for (const char* probe : {"readinessProbe", "livenessProbe"})
      EXPECT_EQ(c.spec[probe]["httpGet"]["port"].as<std::string>(), "http") << c.where << " " << probe;
    EXPECT_EQ(c.spec["readinessProbe"]["httpGet"]["path"].as<std::string>(), "/readyz") << c.where;
    EXPECT_EQ(c.spec["livenessProbe"]["httpGet"]["path"].as<std::string>(), "/livez") << c.where;

    const ManifestServer server(c);
    ASSERT_GT(server.port(), 0) << c.where << ": the server did not start with the manifest's flags; it said:\n" << server.said();
    EXPECT_EQ(answer(server.port(), c.spec["readinessProbe"]["httpGet"]["path"].as<std::string>()), 200) << c.where;
    EXPECT_EQ(answer(server.port(), c.spec["livenessProbe"]["httpGet"]["path"].as<std::string>()), 200) << c.where;
  }
  EXPECT_EQ(servers, 2);
}

TEST(K8sManifests, ObjectsPointAtEachOther) {
  const auto deployments = of_kind("Deployment");
  const auto labels_of = [&](const std::string& name) {
    for (const auto& d : deployments)
      if (d.name() == name) return d.doc["spec"]["template"]["metadata"]["labels"];
    return YAML::Node();
  };
  for (const auto& d : deployments)
    EXPECT_TRUE(labels_match(d.doc["spec"]["selector"]["matchLabels"], labels_of(d.name()))) << d.name() << " selects other pods";
  std::map<std::string, std::set<std::string>> service_ports;
  for (const auto& s : of_kind("Service")) {
    bool selects = false;
    for (const auto& d : deployments) selects |= labels_match(s.doc["spec"]["selector"], labels_of(d.name()));
    EXPECT_TRUE(selects) << "service " << s.name() << " selects no deployment's pods";
    for (const auto& p : s.doc["spec"]["ports"]) service_ports[s.name()].insert(p["name"].as<std::string>());
  }
  for (const auto& i : of_kind("Ingress"))
    for (const auto& rule : i.doc["spec"]["rules"])
      for (const auto& path : rule["http"]["paths"]) {
        const auto service = path["backend"]["service"];
        EXPECT_TRUE(service_ports[service["name"].as<std::string>()].contains(service["port"]["name"].as<std::string>())) << i.name();
      }
  for (const auto& h : of_kind("HorizontalPodAutoscaler"))
    EXPECT_TRUE(labels_of(h.doc["spec"]["scaleTargetRef"]["name"].as<std::string>())) << "the autoscaler scales no deployment";
  for (const auto& p : of_kind("PodDisruptionBudget"))
    EXPECT_TRUE(labels_match(p.doc["spec"]["selector"]["matchLabels"], labels_of("shadelab"))) << "the budget covers no replica";
}

// The ingress is the local cluster's nginx on Kubernetes: the same limits, from the same sources.
TEST(K8sManifests, IngressLimitsAreTheLocalFrontsAndTheReplicas) {
  const auto ingresses = of_kind("Ingress");
  ASSERT_EQ(ingresses.size(), 1u);
  const auto a = ingresses[0].doc["metadata"]["annotations"];
  const auto annotation = [&](const std::string& key) { return a["nginx.ingress.kubernetes.io/" + key].as<std::string>(); };
  const std::string serve_help = run_output(std::string(SHADELAB_CLI) + " serve --help 2>&1");
  const std::string template_text = read_text(kSource / "deploy/nginx/shadelab.conf.template");
  const std::string cluster_sh = read_text(kSource / "tools/cluster.sh");
  const auto one = [](const std::string& text, const std::string& pattern) {
    const auto found = matches(text, pattern);
    return found.empty() ? std::string("(not found)") : *found.begin();
  };

  EXPECT_EQ(annotation("proxy-body-size"), one(serve_help, R"(--max-body-mb UINT=([0-9]+))") + "m");
  EXPECT_EQ(annotation("proxy-next-upstream"), one(template_text, R"(proxy_next_upstream ([a-z_0-9 ]+);)"));
  EXPECT_EQ(annotation("proxy-next-upstream-tries"), one(template_text, R"(proxy_next_upstream_tries ([0-9]+);)"));
  EXPECT_EQ(annotation("proxy-read-timeout") + "s", one(template_text, R"(proxy_read_timeout ([0-9]+s);)"));
  EXPECT_EQ(annotation("limit-connections"), one(cluster_sh, R"(SHADELAB_NGINX_CONNECTIONS_PER_ADDRESS:-([0-9]+))"));
  EXPECT_EQ(annotation("limit-rps"), one(cluster_sh, R"(SHADELAB_NGINX_API_RATE:-([0-9]+))"));

  // The controller's own timeouts: the replicas' head deadline and keep-alive, in seconds.
  for (const auto& m : of_kind("ConfigMap")) {
    if (m.name() != "ingress-nginx-controller") continue;
    const auto ms = [&](const std::string& flag) { return std::to_string(std::stoi(one(serve_help, flag + R"( INT=([0-9]+))")) / 1000); };
    EXPECT_EQ(m.doc["data"]["client-header-timeout"].as<std::string>(), ms("--head-timeout-ms"));
    EXPECT_EQ(m.doc["data"]["client-body-timeout"].as<std::string>(), ms("--body-timeout-ms"));
    EXPECT_EQ(m.doc["data"]["keep-alive"].as<std::string>(), ms("--keep-alive-ms"));
  }
}

TEST(K8sManifests, TheIndexedJobsShardsCoverTheClass) {
  const auto jobs = of_kind("Job");
  ASSERT_EQ(jobs.size(), 1u);
  const auto& spec = jobs[0].doc["spec"];
  EXPECT_EQ(spec["completionMode"].as<std::string>(), "Indexed");
  const Container c{jobs[0].name(), spec["template"]["spec"]["containers"][0]};
  EXPECT_EQ(c.command(), "grade");
  EXPECT_EQ(c.flag("--shard"), "$(JOB_COMPLETION_INDEX)/" + spec["completions"].as<std::string>());
  EXPECT_FALSE(c.flag("--server").empty());
}

}  // namespace
