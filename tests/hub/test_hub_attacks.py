"""Attack tests on a real class hub (`python -m course_lib hub`): another account of the host
cannot reach a learner's lab, neither through ROS 2 (their domain id) nor through TCP, nor
stop one by binding the domain lease ports.

One of them binds every domain lease port of its host, which would leave no domain to the
other tests running beside it: test_hub_attacks_own_network.py runs this module in a network
namespace of its own (its own loopback and ports), with its own hub.

The victim signs in over HTTP and starts, in a real lab terminal, what a lab runs: the
tutorial's node, turtlesim (its window's web port) and the 3D view's server. The attacker is
another learner of the class acting from a shell of their own on the host (not from their
lab), with the course's real `ros2` over real DDS.
"""

from __future__ import annotations

import os
import pwd
import re
import subprocess
import tempfile
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
import requests
from class_hub import ClassHub, server_token
from hub_accounts import as_account, environ_of, lab_terminal, server_pid, sign_in, tcp_listeners
from lab_terminal import RestTerminal

from course_lib.hub.launcher import WALL_PREFIX
from course_lib.processes.domain import candidate_domains, lease_port

OWN_NETWORK_ENV = "COURSE_TEST_OWN_NETWORK"
pytestmark = [
    pytest.mark.ros,
    pytest.mark.slow,
    pytest.mark.learners_env,
    pytest.mark.skipif(
        os.environ.get(OWN_NETWORK_ENV) != "1",
        reason="run by test_hub_attacks_own_network.py, in a network namespace of their own",
    ),
]

VICTIM, INTRUDER, LATECOMER, ADMIN = "r2pw-vic", "r2pw-eve", "r2pw-lee", "r2pw-adm"
_LOOK = (
    "import rclpy, time; rclpy.init(); node = rclpy.create_node('eve'); time.sleep(5); "
    "print('rclpy saw', node.get_node_names_and_namespaces())"
)
_HOLD_LEASES = """
import socket, sys, time
held = []
for port in map(int, sys.argv[1:]):
    s = socket.socket()
    try:
        s.bind(("127.0.0.1", port)); held.append(s)
    except OSError:
        s.close()
print(len(held), flush=True)
time.sleep(3600)
"""


@pytest.fixture(scope="module")
def class_hub(tmp_path_factory: pytest.TempPathFactory) -> Iterator[ClassHub]:
    if os.geteuid() != 0:
        pytest.skip("a class hub creates Unix accounts: run as root (CI does)")
    folder = tmp_path_factory.mktemp("wall-hub")
    started = ClassHub((VICTIM, INTRUDER, LATECOMER), (ADMIN,), folder)
    try:
        yield started
    finally:
        (folder / "hub.log").write_text(started.log(), encoding="utf-8")
        started.stop()  # removes the accounts


# Fast DDS's shared-memory transport fails between accounts (its segments are their owner's),
# and localhost discovery alone met no node of another account here: an attacker uses UDP
# alone and announces itself by multicast too (both found the learner's nodes on main).
_UDP_ONLY = """<?xml version="1.0" encoding="UTF-8"?>
<profiles xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <transport_descriptors>
    <transport_descriptor><transport_id>udp</transport_id><type>UDPv4</type></transport_descriptor>
  </transport_descriptors>
  <participant profile_name="udp_only" is_default_profile="true">
    <rtps>
      <userTransports><transport_id>udp</transport_id></userTransports>
      <useBuiltinTransports>false</useBuiltinTransports>
    </rtps>
  </participant>
</profiles>
"""


def server_socket(hub: ClassHub, name: str) -> Path:
    """Return the path of `name`'s server socket, in their folder of the hub's sockets."""
    run = Path("/run") if Path("/run").is_dir() else Path(tempfile.gettempdir())
    return run / f"{WALL_PREFIX}{hub.port}" / name / "server.sock"


def _intruder_env(hub: ClassHub, domain: str) -> dict[str, str]:
    venv_bin = hub.environment / "course" / ".venv" / "bin"
    account = pwd.getpwnam(INTRUDER)
    profile = Path(account.pw_dir) / "udp_only.xml"
    profile.write_text(_UDP_ONLY, encoding="utf-8")
    os.chown(profile, account.pw_uid, account.pw_gid)
    return {
        "FASTRTPS_DEFAULT_PROFILES_FILE": str(profile),
        "PATH": f"{venv_bin}:{os.defpath}",
        "ROS_DOMAIN_ID": domain,
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET",  # announced by multicast as well
        "ROS_LOG_DIR": str(Path(pwd.getpwnam(INTRUDER).pw_dir) / "ros-log"),
    }


@pytest.fixture
def leases_held(class_hub: ClassHub) -> Iterator[None]:
    """The intruder binds every domain lease port of the host before a learner signs in."""
    ports = [str(lease_port(d)) for d in candidate_domains(1)]
    account = pwd.getpwnam(INTRUDER)

    def become() -> None:
        os.setgroups([])
        os.setgid(account.pw_gid)
        os.setuid(account.pw_uid)

    holder = subprocess.Popen(
        ["/usr/bin/python3", "-c", _HOLD_LEASES, *ports], preexec_fn=become,
        stdout=subprocess.PIPE, text=True, env={"PATH": os.defpath},
    )  # fmt: skip
    assert holder.stdout is not None
    assert int(holder.stdout.readline()) > 100, "the intruder could not hold the leases"
    try:
        yield
    finally:
        holder.kill()
        holder.wait()
        holder.stdout.close()


@pytest.fixture(scope="module")
def victim_lab(class_hub: ClassHub) -> Iterator[RestTerminal]:
    """The victim signed in, with param_vel_node, turtlesim and a 3D view running."""
    sign_in(class_hub, VICTIM)
    terminal = lab_terminal(class_hub, VICTIM)
    try:
        terminal.run(
            "ros2 run parameter_tests param_vel > ~/param_vel.log 2>&1 & "
            "ros2 run turtlesim turtlesim_node > ~/turtlesim.log 2>&1 & "
            "python -m course_lib.viz.server > ~/view.log 2>&1 & echo started",
            r"started",
        )
        terminal.run(
            "for i in $(seq 60); do ros2 node list > ~/nodes.txt; grep -q turtlesim ~/nodes.txt "
            "&& grep -q param_vel ~/nodes.txt && grep -q web_url ~/view.log && break; sleep 1; "
            "done; echo nodes-$(wc -l < ~/nodes.txt)",
            r"nodes-\d+",
            timeout=90,
        )
        terminal.run(
            "cat ~/nodes.txt ~/view.log; echo listed; cat ~/turtlesim.log",
            r"/turtlesim[\s\S]*listed",
        )
        yield terminal
    finally:
        terminal.close()


def test_bound_lease_ports_leave_a_hub_learner_working(
    class_hub: ClassHub, leases_held: None
) -> None:
    """The hub gives each learner their domain and holds it: the leases, which another
    account can bind, serve single-user labs only."""
    sign_in(class_hub, LATECOMER, timeout=90.0)
    terminal = lab_terminal(class_hub, LATECOMER)
    try:
        domain = environ_of(server_pid(LATECOMER))["ROS_DOMAIN_ID"]
        assert terminal.run("echo domain=$ROS_DOMAIN_ID", rf"domain={domain}\b")
        terminal.run(
            "ros2 run parameter_tests param_vel > ~/param_vel.log 2>&1 & for i in $(seq 30); "
            "do ros2 node list | grep -q param_vel && break; sleep 1; done; echo waited",
            r"waited",
            timeout=60,
        )
        assert terminal.run("ros2 node list; echo listed", r"/param_vel_node\s[\s\S]*listed")
    finally:
        terminal.close()


def test_another_account_with_the_learners_domain_sees_and_drives_nothing(
    class_hub: ClassHub, victim_lab: RestTerminal
) -> None:
    domain = victim_lab.run("echo domain=$ROS_DOMAIN_ID", r"domain=(\d+)")[1]
    env = _intruder_env(class_hub, domain)
    # the course's ros2 (its daemon given time to discover) and a plain rclpy node
    listing = 'ros2 node list > /dev/null; sleep 4; ros2 node list; python -c "$LOOK"'
    nodes = as_account(INTRUDER, ["sh", "-c", listing], {**env, "LOOK": _LOOK}, timeout=90)
    assert nodes.returncode == 0, f"the intruder's ros2 did not run: {nodes.stderr}"
    assert "rclpy saw" in nodes.stdout, nodes.stdout + nodes.stderr
    assert "param_vel_node" not in nodes.stdout, f"the intruder sees: {nodes.stdout}"
    assert "turtlesim" not in nodes.stdout, f"the intruder sees: {nodes.stdout}"
    setting = ["ros2", "param", "set", "/param_vel_node", "velocity", "0.37"]
    as_account(INTRUDER, setting, env)
    got = victim_lab.run("ros2 param get /param_vel_node velocity", r"value is: (\S+)")
    assert got[1] != "0.37", "the intruder set the learner's parameter"
    # the victim listens on /cmd_vel while the intruder publishes on it, then publishes there
    # themselves (the control: the listener hears what reaches it)
    victim_lab.run(
        "timeout 16 ros2 topic echo /cmd_vel > ~/cmd_vel.txt 2>&1 & echo listening", r"listening"
    )
    twist = ["geometry_msgs/msg/Twist", "{linear: {x: 0.5}}"]
    as_account(
        INTRUDER, ["timeout", "6", "ros2", "topic", "pub", "-r", "5", "/cmd_vel", *twist], env
    )
    victim_lab.run(
        "timeout 4 ros2 topic pub -r 5 /cmd_vel geometry_msgs/msg/Twist '{linear: {x: 0.125}}' "
        "> /dev/null 2>&1; sleep 7; cat ~/cmd_vel.txt; echo heard-end",
        r"heard-end",
    )
    heard = victim_lab.output[-6000:]
    assert "x: 0.125" in heard, f"the victim's own listener heard nothing: {heard[-1500:]}"
    assert "x: 0.5" not in heard, "the intruder drove the learner's robot"


def test_another_account_reaches_no_tcp_port_of_the_learners_lab(
    class_hub: ClassHub, victim_lab: RestTerminal
) -> None:
    victim = pwd.getpwnam(VICTIM).pw_uid
    pid = server_pid(VICTIM)
    ports = tcp_listeners(pid, victim)
    assert len(ports) >= 2, f"the lab should listen (turtlesim window, 3D view): {ports}"
    host = tcp_listeners(os.getpid(), victim)  # the learner's ports seen from the host
    code = "import socket,sys; print([p for p in map(int, sys.argv[1:]) if socket.socket()" \
        ".connect_ex(('127.0.0.1', p)) == 0])"  # fmt: skip
    reached = as_account(INTRUDER, ["/usr/bin/python3", "-c", code, *map(str, ports)], {})
    opened = [int(p) for p in re.findall(r"\d+", reached.stdout)]
    # a port number some other program of the host happens to use is not the learner's
    theirs = [p for p in opened if p in host]
    assert not theirs, f"another account connected to the learner's ports {theirs} (all {ports})"
    assert not host, f"the learner's lab listens on the host's network: {host}"


def test_the_progress_service_runs_as_its_own_account_not_root(class_hub: ClassHub) -> None:
    """It ran as root, on a port picked free, released, and bound again later by the service
    (another account could take it in between and receive the learners' records and tokens)."""
    from course_lib.hub.progress_service import SERVICE_ACCOUNT

    found = []
    ours = str(class_hub.state.parent).encode()  # this hub's folder: another test's hub may run
    for entry in Path("/proc").iterdir():
        try:
            command = (entry / "cmdline").read_bytes().split(b"\0")
            mine = any(arg.startswith(ours) for arg in command)
            if entry.name.isdigit() and b"course_lib.hub.progress" in command and mine:
                found.append((entry.stat().st_uid, command))
        except OSError:
            continue
    assert found, "no progress service runs"
    account = pwd.getpwnam(SERVICE_ACCOUNT).pw_uid
    learners = {pwd.getpwnam(n).pw_uid for n in (VICTIM, INTRUDER, LATECOMER, ADMIN)}
    assert [uid for uid, _ in found] == [account], found
    assert account != 0 and account not in learners
    assert all(b"--listen-fd" in command for _, command in found), "handed its socket"


def _status(url: str, headers: dict[str, str]) -> int:
    return requests.get(url, headers=headers, timeout=30).status_code


def test_a_link_in_a_learners_socket_folder_routes_nothing_to_another_server(
    class_hub: ClassHub, victim_lab: RestTerminal
) -> None:
    """The proxy (root) followed a symbolic link the intruder put in place of their own
    server.sock to the victim's socket: 99 of 120 of the intruder's requests were answered by
    the victim's server, and kept-alive connections kept that route once the link was gone.
    The hub routes to a hard link of the socket the intruder's server listens on, made by root
    in a folder of its own: every request reaches the intruder's own server."""
    sign_in(class_hub, INTRUDER)
    sockets = server_socket(class_hub, INTRUDER).parent
    victims = server_socket(class_hub, VICTIM)
    swap = f"rm -f {sockets}/server.sock && ln -s {victims} {sockets}/server.sock && echo linked"
    swapped = as_account(INTRUDER, ["/bin/sh", "-c", swap], {})
    assert swapped.stdout.strip() == "linked", swapped.stderr
    status = f"{class_hub.url}/user/{INTRUDER}/api/status"
    token = {"Authorization": f"token {server_token(INTRUDER)}"}
    # at once, as a lab's page does: the proxy opens new connections to the route
    with ThreadPoolExecutor(24) as pool:
        codes = list(pool.map(lambda _: _status(status, token), range(120)))
    assert codes.count(200) == 120, f"answered elsewhere: {codes.count(200)} of 120 were 200"
    gone = as_account(INTRUDER, ["rm", "-f", f"{sockets}/server.sock"], {})
    assert gone.returncode == 0, gone.stderr
    again = [requests.get(status, headers=token, timeout=30).status_code for _ in range(20)]
    assert again == [200] * 20, again
