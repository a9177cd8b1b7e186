#include "server_process.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

namespace ncpost::test {
namespace {

std::filesystem::path binary_dir() {
  if (const char* env = std::getenv("NCPOST_BINARY_DIR"); env && *env) return env;
#ifdef NCPOST_BINARY_DIR
  return NCPOST_BINARY_DIR;
#else
  return std::filesystem::current_path();
#endif
}

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string shell_quote(std::string_view s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

// The port in the first {"listening":"127.0.0.1:PORT"} line, 0 when there is none yet.
int find_port(const std::string& log) {
  const std::string key = "\"listening\":\"127.0.0.1:";
  const auto at = log.find(key);
  if (at == std::string::npos) return 0;
  int port = 0;
  for (std::size_t i = at + key.size();
       i < log.size() && std::isdigit(static_cast<unsigned char>(log[i])); ++i)
    port = port * 10 + (log[i] - '0');
  return port;
}

std::optional<int> decode_status(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return std::nullopt;
}

}  // namespace

std::filesystem::path ncpostd_path() {
  if (const char* env = std::getenv("NCPOSTD"); env && *env) return env;
  return binary_dir() / "bin" / "ncpostd";
}

std::filesystem::path ncpost_path() {
  if (const char* env = std::getenv("NCPOST"); env && *env) return env;
  return binary_dir() / "bin" / "ncpost";
}

TempDir::TempDir() {
  std::random_device rd;
  const auto base = std::filesystem::temp_directory_path();
  for (;;) {
    path_ = base / ("ncpost-it-" + std::to_string(::getpid()) + "-" + std::to_string(rd()));
    std::error_code ec;
    if (std::filesystem::create_directory(path_, ec)) break;
  }
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

ServerProcess::ServerProcess(ServerOptions options) {
  static std::atomic<int> counter{0};
  dir_ = std::filesystem::temp_directory_path() /
         ("ncpostd-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::create_directories(dir_);
  log_path_ = dir_ / "server.log";

  std::vector<std::string> argv_storage = {ncpostd_path().string(), "--listen", "127.0.0.1:0"};
  argv_storage.insert(argv_storage.end(), options.args.begin(), options.args.end());
  std::vector<char*> argv;
  for (auto& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log_file = log_path_.string();

  pid_ = ::fork();
  if (pid_ == 0) {
    // The server must not outlive a test runner that crashed.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    const int fd = ::open(log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::close(fd);
    }
    for (const auto& [name, value] : options.env) ::setenv(name.c_str(), value.c_str(), 1);
    ::execv(argv[0], argv.data());
    std::perror("execv ncpostd");
    ::_exit(127);
  }
  if (pid_ < 0) return;
  const auto deadline = std::chrono::steady_clock::now() + options.start_timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    port_ = find_port(slurp(log_path_));
    if (port_ != 0) return;
    if (!running()) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

ServerProcess::~ServerProcess() {
  if (pid_ > 0 && !status_) stop();
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
}

std::string ServerProcess::url(std::string_view path) const {
  return "http://127.0.0.1:" + std::to_string(port_) + std::string(path);
}

std::string ServerProcess::log() const {
  return slurp(log_path_);
}

void ServerProcess::signal(int sig) const {
  if (pid_ > 0 && !status_) ::kill(pid_, sig);
}

bool ServerProcess::running() {
  if (pid_ <= 0 || status_) return false;
  int status = 0;
  const pid_t r = ::waitpid(pid_, &status, WNOHANG);
  if (r == pid_) {
    status_ = decode_status(status).value_or(-1);
    return false;
  }
  return r == 0;
}

std::optional<int> ServerProcess::wait(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (running()) {
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return status_;
}

std::optional<int> ServerProcess::stop(std::chrono::milliseconds deadline) {
  if (pid_ <= 0) return std::nullopt;
  signal(SIGTERM);
  if (auto status = wait(deadline)) return status;
  signal(SIGKILL);
  return wait(std::chrono::seconds(5));
}

std::string CurlResult::header(std::string_view name) const {
  std::istringstream in(headers);
  std::string line;
  std::string found;
  const auto lower = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
  };
  const std::string want = lower(std::string(name));
  while (std::getline(in, line)) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    if (lower(line.substr(0, colon)) != want) continue;
    std::string value = line.substr(colon + 1);
    while (!value.empty() && (value.front() == ' ' || value.front() == '\t')) value.erase(0, 1);
    while (!value.empty() && (value.back() == '\r' || value.back() == '\n' || value.back() == ' '))
      value.pop_back();
    found = value;  // the last response's value wins (after a 100 Continue, say)
  }
  return found;
}

CurlResult curl(const std::vector<std::string>& args) {
  TempDir dir;
  const auto headers = dir.path() / "headers";
  const auto body = dir.path() / "body";
  std::string command = "curl -sS -o " + shell_quote(body.string()) + " -D " +
                        shell_quote(headers.string()) + " -w '%{http_code}'";
  if (std::find(args.begin(), args.end(), "--max-time") == args.end()) command += " --max-time 60";
  for (const auto& a : args) command += " " + shell_quote(a);
  command += " 2>" + shell_quote((dir.path() / "stderr").string());
  CurlResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::string out;
  char buffer[256];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = ::pclose(pipe);
  result.exit_code = decode_status(status).value_or(-1);
  result.status = std::atoi(out.c_str());
  result.headers = slurp(headers);
  result.body = slurp(body);
  return result;
}

RawConnection::RawConnection(int port) {
  fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd_ < 0) return;
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

RawConnection::~RawConnection() {
  close();
}

bool RawConnection::send(std::string_view bytes) {
  while (!bytes.empty()) {
    if (fd_ < 0) return false;
    const ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    if (n <= 0) return false;
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

std::string RawConnection::receive(std::chrono::milliseconds timeout, std::size_t max) {
  if (fd_ < 0 || closed_) return {};
  pollfd p{fd_, POLLIN, 0};
  if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return {};
  std::string out(max, '\0');
  const ssize_t n = ::recv(fd_, out.data(), out.size(), 0);
  if (n <= 0) {
    closed_ = true;
    return {};
  }
  out.resize(static_cast<std::size_t>(n));
  return out;
}

std::string RawConnection::receive_until(std::string_view needle,
                                         std::chrono::milliseconds timeout) {
  std::string all;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (all.find(needle) == std::string::npos && !closed_) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    all += receive(left);
  }
  return all;
}

void RawConnection::close(bool reset) {
  if (fd_ < 0) return;
  if (reset) {
    linger l{1, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_LINGER, &l, sizeof l);
  }
  ::close(fd_);
  fd_ = -1;
}

}  // namespace ncpost::test
