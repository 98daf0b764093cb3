// slamer-launch's library: the launch file format and its problems (one line
// each, naming file and key), --check of what a file names with each program's
// own loader, the supervisord.conf it generates, supervisor's XML-RPC replies,
// and the start/stop order.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test/support/temp_dir.hpp"
#include "tools/launch/launch_check.hpp"
#include "tools/launch/launch_file.hpp"
#include "tools/launch/launch_sequence.hpp"
#include "tools/launch/program_help.hpp"
#include "tools/launch/supervisor_conf.hpp"
#include "tools/launch/xmlrpc.hpp"

namespace slamer::launch {
namespace {

namespace fs = std::filesystem;
const std::string kSource = SLAMER_SOURCE_DIR;
const std::string kBin = std::string(SLAMER_BINARY_DIR "/bin");

std::vector<std::string> search() {
  return {kBin, "/usr/bin", "/bin"};
}

using test::TempDir;

TEST(LaunchFile, ReadsEveryKeyAndResolvesTheConfigAgainstTheFile) {
  std::vector<std::string> problems;
  const LaunchFile f = parse_launch_file(
      "lcm_url: udpm://239.255.76.67:7667?ttl=0\nlog_dir: logs\nprocesses:\n"
      "  - {name: a, program: slamer-urg, config: urg.yaml, args: [--host, x], group: 2, respawn: false,\n"
      "     required: true, lcm: false, start_seconds: 3, start_retries: 7, stop_timeout: 4, enabled: false}\n"
      "  - {name: b, program: lcm-logger}\n",
      "x.yaml", &problems);
  ASSERT_TRUE(problems.empty()) << problems[0];
  EXPECT_EQ(f.lcm_url, "udpm://239.255.76.67:7667?ttl=0");
  EXPECT_EQ(f.log_dir, "logs");
  ASSERT_EQ(f.processes.size(), 2u);
  const LaunchProcess& a = f.processes[0];
  // A string source has no directory: the working one; absolute, since the processes run elsewhere.
  EXPECT_EQ(a.config, std::filesystem::absolute("urg.yaml").string());
  EXPECT_EQ(a.args, (std::vector<std::string>{"--host", "x"}));
  EXPECT_EQ(a.group, 2);
  EXPECT_FALSE(a.respawn);
  EXPECT_TRUE(a.required);
  EXPECT_FALSE(a.lcm);
  EXPECT_FALSE(a.enabled);
  EXPECT_EQ(a.start_seconds, 3);
  EXPECT_EQ(a.start_retries, 7);
  EXPECT_EQ(a.stop_timeout, 4);
  EXPECT_TRUE(f.processes[1].respawn);
  EXPECT_EQ(f.processes[1].group, 0);

  TempDir dir("slamer_launch_test");
  fs::create_directories(dir.path() + "/launch");
  const LaunchFile g = read_launch_file(
      dir.write("launch/l.yaml", "processes: [{name: a, program: p, config: ../c.yaml}]\n"), &problems);
  EXPECT_EQ(g.processes.at(0).config, dir.path() + "/c.yaml");
}

TEST(LaunchFile, EveryProblemIsOneLineNamingFileAndKey) {
  std::vector<std::string> problems;
  parse_launch_file(
      "lcm_ur: x\n"  // unknown top-level key
      "processes:\n"
      "  - {name: a, program: p, grup: 1}\n"                          // unknown process key
      "  - {program: p}\n"                                            // no name
      "  - {name: a, program: q}\n"                                   // duplicate
      "  - {name: 'b c', program: p, group: -1}\n"                    // bad name, bad group
      "  - {name: d, program: p, args: [--config, x.yaml]}\n"         // --config in args
      "  - {name: e, program: p, args: ['${home}/x']}\n"              // unknown expansion
      "  - {name: f, program: p, start_retries: many, respawn: 3}\n"  // two bad values
      "  - {name: g}\n",                                              // no program
      "bad.yaml", &problems);
  const std::vector<std::pair<int, std::string>> expected = {
      {1, "key 'lcm_ur': unknown key"},
      {3, "key 'processes[0].grup': unknown key"},
      {4, "key 'processes[1].name': missing"},
      {5, "key 'processes[2].name': duplicate name 'a' (first at bad.yaml:3"},
      {6, "key 'processes[3].name': 'b c' is not a name"},
      {6, "key 'processes[3].group': expected an integer (a number in [0, 99]), got '-1'"},
      {7, "key 'processes[4].args': argument 1 '--config': give the config file as the process's 'config' key"},
      {8, "key 'processes[5].args': argument 1: unknown '${home}'"},
      {9, "key 'processes[6].respawn': expected true or false"},
      {9, "key 'processes[6].start_retries': expected"},
      {10, "key 'processes[7].program': missing"},
  };
  ASSERT_EQ(problems.size(), expected.size()) << ::testing::PrintToString(problems);
  for (const auto& [line, text] : expected) {
    const std::string prefix = "bad.yaml:" + std::to_string(line) + ": " + text;
    bool found = false;
    for (const std::string& p : problems) {
      found = found || p.rfind(prefix, 0) == 0;
      EXPECT_EQ(p.find('\n'), std::string::npos) << p;
    }
    EXPECT_TRUE(found) << "no problem starts with: " << prefix << "\n" << ::testing::PrintToString(problems);
  }
}

TEST(LaunchFile, NoProcessesOrNoneEnabledIsAProblem) {
  for (const std::string text : {"lcm_url: x\n", "processes: []\n",
                                 "processes: [{name: a, program: p, enabled: false}]\n", "processes: [ {name: a\n"}) {
    std::vector<std::string> problems;
    parse_launch_file(text, "f.yaml", &problems);
    ASSERT_EQ(problems.size(), 1u) << text;
    EXPECT_EQ(problems[0].rfind("f.yaml", 0), 0u) << problems[0];
  }
}

TEST(LaunchFile, ExpandsOnlyLogAndRunDir) {
  const Directories dirs{"/x", "/l", "/r", "/s"};
  EXPECT_EQ(expand("${log_dir}/a-${run_dir}${state_dir}", dirs), "/l/a-/r/s");
  EXPECT_EQ(expand("plain", dirs), "plain");
  EXPECT_THROW(expand("${log_dir", dirs), std::invalid_argument);
  EXPECT_THROW(expand("${LOG_DIR}", dirs), std::invalid_argument);
  EXPECT_EQ(flag_value({"--map", "m.yaml", "--x=1"}, "--map"), "m.yaml");
  EXPECT_EQ(flag_value({"--map=m.yaml"}, "--map"), "m.yaml");
  EXPECT_EQ(flag_value({"--mapx", "y"}, "--map"), "");
}

TEST(LaunchCheck, NamesTheConfigAndKeyOfWhatDoesNotLoad) {
  TempDir dir("slamer_launch_test");
  dir.write("recognizer.yaml", "channels:\n  lidar: LIDAR\n  line_object: X\n");
  dir.write("localizer.yaml", "map: nowhere/map.yaml\n");
  const std::string launch =
      dir.write("l.yaml",
                "processes:\n"
                "  - {name: rec, program: slamer-recognizer, config: recognizer.yaml}\n"
                "  - {name: loc, program: slamer-localizer, config: localizer.yaml}\n"
                "  - {name: loc2, program: slamer-localizer, config: localizer.yaml, args: [--map, " +
                    kSource +
                    "/config/maps/small_room/map.yaml]}\n"
                    "  - {name: log, program: lcm-logger, config: localizer.yaml}\n"
                    "  - {name: nope, program: slamer-no-such-program}\n"
                    "  - {name: missing, program: slamer-urg, config: urg_missing.yaml}\n"
                    "  - {name: sim, program: slamer-sim}\n"
                    "  - {name: flags, program: slamer-urg, args: [--host, h, --hots, h, '--port=1']}\n");
  const std::vector<std::string> problems = check_launch_file(launch, search());
  ASSERT_EQ(problems.size(), 7u) << ::testing::PrintToString(problems);
  EXPECT_EQ(problems[0].rfind(dir.path() + "/recognizer.yaml:3: unknown key 'channels.line_object'", 0), 0u)
      << problems[0];
  EXPECT_NE(problems[0].find("process 'rec', " + launch + ":2: key 'processes[0].config'"), std::string::npos);
  EXPECT_NE(problems[1].find("nowhere/map.yaml"), std::string::npos) << problems[1];
  EXPECT_NE(problems[1].find("process 'loc'"), std::string::npos) << problems[1];
  EXPECT_EQ(problems[2].rfind(launch + ":5: key 'processes[3].config': slamer-launch cannot check a config", 0), 0u)
      << problems[2];
  EXPECT_EQ(problems[3].rfind(launch + ":6: key 'processes[4].program': program 'slamer-no-such-program' not found", 0),
            0u)
      << problems[3];
  EXPECT_EQ(problems[4].rfind(launch + ":7: key 'processes[5].config': '" + dir.path() + "/urg_missing.yaml'", 0), 0u)
      << problems[4];
  EXPECT_NE(problems[5].find("--world FILE is required"), std::string::npos) << problems[5];
  EXPECT_EQ(problems[6], launch + ":9: key 'processes[7].args': 'slamer-urg' does not list --hots in its --help");
}

TEST(LaunchCheck, OptionsAreComparedWithWhatTheHelpLists) {
  const std::string help = "usage: x [--lcm-url URL] [--map FILE]\n  -i, --increment  more\n  --map-dir D\n";
  EXPECT_EQ(unlisted_options({"--map", "m", "--lcm-url=u", "-i", "--increment", "plain", "--"}, help),
            std::vector<std::string>{});
  EXPECT_EQ(unlisted_options({"--ma", "--map-di", "--mapx=1", "--lcm"}, help),
            (std::vector<std::string>{"--ma", "--map-di", "--mapx", "--lcm"}));
  EXPECT_TRUE(unlisted_options({"--anything"}, "usage: y FILE\n").empty());  // lists nothing: not compared
  EXPECT_NE(program_help(kBin + "/slamer-recognizer").find("--replay"), std::string::npos);
  EXPECT_EQ(program_help("/nonexistent/program"), "");
}

TEST(SupervisorConf, OneProgramPerEnabledProcessQuotedAsShlexReadsIt) {
  EXPECT_EQ(quote_argument("it's 5%"), "'it'\"'\"'s 5%%'");
  std::vector<std::string> problems;
  const LaunchFile f = parse_launch_file(
      "lcm_url: udpm://239.255.76.67:7667?ttl=0\nprocesses:\n"
      "  - {name: log, program: lcm-logger, args: ['${log_dir}/x.lcm'], enabled: false}\n"
      "  - {name: loc, program: slamer-localizer, config: /c/loc.yaml, group: 3, respawn: false, stop_timeout: 7}\n"
      "  - {name: raw, program: sleep, args: ['1'], lcm: false, start_seconds: 0}\n",
      "f.yaml", &problems);
  ASSERT_TRUE(problems.empty());
  const Directories dirs{"/launch", "/logs", "/run", "/state"};
  const auto loc = process_argv(f.processes[1], "/bin/slamer-localizer", f.lcm_url, dirs);
  EXPECT_EQ(loc, (std::vector<std::string>{"/bin/slamer-localizer", "--config", "/c/loc.yaml",
                                           "--lcm-url=udpm://239.255.76.67:7667?ttl=0"}));
  EXPECT_EQ(process_argv(f.processes[0], "/usr/bin/lcm-logger", f.lcm_url, dirs).back(), "/logs/x.lcm");
  const auto raw = process_argv(f.processes[2], "/bin/sleep", f.lcm_url, dirs);
  EXPECT_EQ(raw, (std::vector<std::string>{"/bin/sleep", "1"}));
  const std::string conf = supervisor_config(f, {loc, raw}, dirs);
  EXPECT_EQ(conf.find("[program:log]"), std::string::npos);
  const std::size_t loc_at = conf.find(
      "[program:loc]\ncommand='/bin/slamer-localizer' '--config' '/c/loc.yaml' "
      "'--lcm-url=udpm://239.255.76.67:7667?ttl=0'\ndirectory=/launch\n"
      "autostart=false\nautorestart=false\nstartsecs=2\nstartretries=5\n"
      "priority=103\nstopsignal=TERM\nstopwaitsecs=7\n");
  EXPECT_NE(loc_at, std::string::npos) << conf;
  EXPECT_NE(conf.find("stdout_logfile=/logs/loc.log"), std::string::npos);
  EXPECT_NE(conf.find("[program:raw]\ncommand='/bin/sleep' '1'\n"), std::string::npos);
  EXPECT_NE(conf.find("[unix_http_server]\nfile=/run/supervisor.sock"), std::string::npos);
  EXPECT_NE(conf.find("autorestart=true\nstartsecs=0"), std::string::npos);
}

// A reply of supervisor 4.2.5's getAllProcessInfo, cut to the fields of two processes.
const std::string kReply =
    "HTTP/1.0 200 OK\r\nServer: Medusa/1.12\r\nContent-Type: text/xml\r\nContent-Length: 1\r\n\r\n"
    "<?xml version='1.0'?>\n<methodResponse>\n<params>\n<param>\n<value><array><data>\n"
    "<value><struct>\n<member>\n<name>name</name>\n<value><string>loc</string></value>\n</member>\n"
    "<member>\n<name>statename</name>\n<value><string>RUNNING</string></value>\n</member>\n"
    "<member>\n<name>pid</name>\n<value><int>4242</int></value>\n</member>\n"
    "<member>\n<name>spawnerr</name>\n<value><string></string></value>\n</member>\n"
    "<member>\n<name>description</name>\n<value><string>pid 4242, uptime 0:00:05 &amp; &lt;ok&gt;</string></value>\n"
    "</member>\n</struct></value>\n"
    "<value><struct>\n<member>\n<name>name</name>\n<value><string>sim</string></value>\n</member>\n"
    "<member>\n<name>statename</name>\n<value><string>EXITED</string></value>\n</member>\n"
    "<member>\n<name>exitstatus</name>\n<value><int>3</int></value>\n</member>\n"
    "<member>\n<name>flag</name>\n<value><boolean>1</boolean></value>\n</member>\n"
    "</struct></value>\n</data></array></value>\n</param>\n</params>\n</methodResponse>\n";

TEST(XmlRpc, ReadsSupervisorsProcessInfo) {
  const std::vector<ProcessInfo> infos = parse_process_infos(parse_xmlrpc_response(http_body(kReply)));
  ASSERT_EQ(infos.size(), 2u);
  EXPECT_EQ(infos[0].name, "loc");
  EXPECT_EQ(infos[0].state, "RUNNING");
  EXPECT_EQ(infos[0].pid, 4242);
  EXPECT_EQ(infos[0].description, "pid 4242, uptime 0:00:05 & <ok>");
  EXPECT_EQ(infos[1].state, "EXITED");
  EXPECT_EQ(infos[1].exit_status, 3);
  EXPECT_EQ(infos[1].pid, 0);
  EXPECT_EQ(xmlrpc_request("supervisor.startProcess",
                           {{XmlRpcParam::Kind::kString, "a<b"}, {XmlRpcParam::Kind::kBool, "", false}}),
            "<?xml version=\"1.0\"?>\n<methodCall><methodName>supervisor.startProcess</methodName><params>"
            "<param><value><string>a&lt;b</string></value></param><param><value><boolean>0</boolean></value>"
            "</param></params></methodCall>\n");
}

TEST(XmlRpc, FaultsAndDamagedRepliesThrowNeverCrash) {
  const std::string fault =
      "<?xml version='1.0'?>\n<methodResponse>\n<fault>\n<value><struct>\n<member>\n<name>faultCode</name>\n"
      "<value><int>60</int></value>\n</member>\n<member>\n<name>faultString</name>\n"
      "<value><string>ALREADY_STARTED: loc</string></value>\n</member>\n</struct></value>\n</fault>\n"
      "</methodResponse>\n";
  try {
    parse_xmlrpc_response(fault);
    ADD_FAILURE() << "a fault must throw";
  } catch (const XmlRpcError& e) {
    EXPECT_EQ(std::string(e.what()), "supervisor: ALREADY_STARTED: loc");
  }
  EXPECT_THROW(http_body("HTTP/1.0 401 Unauthorized\r\n\r\n"), XmlRpcError);
  // Every cut of the reply, and one byte changed at each place: parsed or XmlRpcError.
  int parsed = 0;
  for (std::size_t n = 0; n <= kReply.size(); ++n) {
    for (const bool flip : {false, true}) {
      std::string damaged = kReply.substr(0, n);
      if (flip && n < kReply.size()) {
        damaged += static_cast<char>(kReply[n] ^ 0x20);
        damaged += kReply.substr(n + 1);
      }
      try {
        parse_process_infos(parse_xmlrpc_response(http_body(damaged)));
        ++parsed;
      } catch (const XmlRpcError&) {
      }
    }
  }
  EXPECT_GT(parsed, 1);  // the whole reply, and changes in text that keep it valid
  std::string deep = "<methodResponse><params><param>";
  for (int i = 0; i < 40; ++i) {
    deep += "<value><array><data>";
  }
  EXPECT_THROW(parse_xmlrpc_response(deep), XmlRpcError);
}

std::vector<ProcessInfo> states(const std::vector<std::pair<std::string, std::string>>& list) {
  std::vector<ProcessInfo> infos;
  for (const auto& [name, state] : list) {
    infos.push_back({name, state, 1, 0, ""});
  }
  return infos;
}

TEST(LaunchSequence, GroupsStartInOrderAndStopInReverse) {
  LaunchSequence s(
      {{"urg", 0, true, true}, {"wheels", 0, true, true}, {"loc", 1, false, true}, {"log", 5, false, true}});
  SequenceActions a =
      s.update(states({{"urg", "STOPPED"}, {"wheels", "STOPPED"}, {"loc", "STOPPED"}, {"log", "STOPPED"}}));
  EXPECT_EQ(a.start, (std::vector<std::string>{"urg", "wheels"}));
  a = s.update(states({{"urg", "RUNNING"}, {"wheels", "STARTING"}, {"loc", "STOPPED"}, {"log", "STOPPED"}}));
  EXPECT_TRUE(a.start.empty());  // wheels not up yet
  a = s.update(states({{"urg", "RUNNING"}, {"wheels", "RUNNING"}, {"loc", "STOPPED"}, {"log", "STOPPED"}}));
  a = s.update(states({{"urg", "RUNNING"}, {"wheels", "RUNNING"}, {"loc", "STOPPED"}, {"log", "STOPPED"}}));
  EXPECT_EQ(a.start, (std::vector<std::string>{"loc"}));
  // A process that is not required and gives up does not hold the start.
  a = s.update(states({{"urg", "RUNNING"}, {"wheels", "RUNNING"}, {"loc", "FATAL"}, {"log", "STOPPED"}}));
  a = s.update(states({{"urg", "RUNNING"}, {"wheels", "RUNNING"}, {"loc", "FATAL"}, {"log", "STOPPED"}}));
  EXPECT_EQ(a.start, (std::vector<std::string>{"log"}));
  a = s.update(states({{"urg", "RUNNING"}, {"wheels", "RUNNING"}, {"loc", "RUNNING"}, {"log", "RUNNING"}}));
  EXPECT_TRUE(s.started());
  s.request_stop("test");
  a = s.update(states({{"urg", "RUNNING"}, {"wheels", "RUNNING"}, {"loc", "RUNNING"}, {"log", "RUNNING"}}));
  EXPECT_EQ(a.stop, (std::vector<std::string>{"log"}));
  a = s.update(states({{"urg", "RUNNING"}, {"wheels", "RUNNING"}, {"loc", "RUNNING"}, {"log", "STOPPING"}}));
  EXPECT_TRUE(a.stop.empty());
  a = s.update(states({{"urg", "RUNNING"}, {"wheels", "RUNNING"}, {"loc", "RUNNING"}, {"log", "STOPPED"}}));
  EXPECT_EQ(a.stop, (std::vector<std::string>{"loc"}));
  // A respawning process that just exited will start again: not gone yet.
  a = s.update(states({{"urg", "RUNNING"}, {"wheels", "RUNNING"}, {"loc", "EXITED"}, {"log", "STOPPED"}}));
  EXPECT_TRUE(a.stop.empty());
  EXPECT_FALSE(s.done());
  a = s.update(states({{"urg", "RUNNING"}, {"wheels", "RUNNING"}, {"loc", "STOPPED"}, {"log", "STOPPED"}}));
  EXPECT_EQ(a.stop, (std::vector<std::string>{"urg", "wheels"}));
  a = s.update(states({{"urg", "STOPPED"}, {"wheels", "STOPPED"}, {"loc", "STOPPED"}, {"log", "STOPPED"}}));
  EXPECT_TRUE(s.done());
  EXPECT_EQ(s.exit_code(), 0);
}

TEST(LaunchSequence, ARequiredProcessEndingStopsTheLaunch) {
  for (const auto& [state, status, code] :
       std::vector<std::tuple<std::string, int, int>>{{"EXITED", 0, 0}, {"EXITED", 2, 1}, {"FATAL", 0, 1}}) {
    LaunchSequence s({{"drv", 0, false, true}, {"sim", 1, true, false}});
    s.update(states({{"drv", "STOPPED"}, {"sim", "STOPPED"}}));
    s.update(states({{"drv", "RUNNING"}, {"sim", "STOPPED"}}));
    s.update(states({{"drv", "RUNNING"}, {"sim", "STOPPED"}}));
    s.update(states({{"drv", "RUNNING"}, {"sim", "RUNNING"}}));
    ASSERT_TRUE(s.started());
    std::vector<ProcessInfo> ended = states({{"drv", "RUNNING"}, {"sim", state}});
    ended[1].exit_status = status;
    const SequenceActions a = s.update(ended);
    EXPECT_TRUE(s.stopping()) << state;
    EXPECT_EQ(a.stop, (std::vector<std::string>{"drv"})) << state;  // sim's group is gone already
    s.update(states({{"drv", "STOPPED"}, {"sim", state}}));
    EXPECT_TRUE(s.done());
    EXPECT_EQ(s.exit_code(), code) << state << " " << status;
  }
}

}  // namespace
}  // namespace slamer::launch
