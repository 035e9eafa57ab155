"""deploy/kubernetes/ cannot run here: keep it consistent with what the local hub runs.

The image, the Zero to JupyterHub values and the progress service's manifest are checked
against the course's own code and figures: the single-user command and default URL of the
local hub, the progress service's name, URL, port and roles, the capacity figures of
deploy/capacity.yaml, the learners and admins of config/hub.yaml, and the Dockerfile's base
image and copied paths. The pure helpers below are also checked on broken inputs.
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import json
import re
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import pytest
import yaml

REPO = Path(__file__).resolve().parents[4]
DEPLOY = REPO / "deploy"
KUBE = DEPLOY / "kubernetes"
DOCKERFILE = REPO / "Dockerfile"  # one image; Kubernetes runs its `singleuser` stage
GUIDE = REPO / "book" / "guides" / "class-on-kubernetes.md"  # how to deploy, what was tested
IMAGE_COURSE = "/opt/ros2-params-course"
IMAGE_PYTHON = f"{IMAGE_COURSE}/.venv/bin/python"
LOCAL_TAIL = ["-m", "course_lib", "hub-lab"]  # after the learner's python, as the local hub
# Fast DDS: 0.5 MiB per participant; a learner's live processes map about 2.5 MiB, killed ones
# leave theirs behind until the pod ends. 128 MiB holds about 230 segments.
SHM_MIN_MIB = 128


# --- pure helpers (checked on broken inputs at the end) -------------------------------------
def names_registry_host(image: str) -> bool:
    """Return True if image reference `image` starts with a registry host (docker's rule)."""
    first, sep, _ = image.partition("/")
    return bool(sep) and ("." in first or ":" in first or first == "localhost")


def mib(quantity: str | int | float) -> float:
    """Return a KubeSpawner byte quantity ("448M", "2G", "256Mi", bytes) in MiB."""
    match = re.fullmatch(r"(\d+(?:\.\d+)?)\s*([KMGT]i?)?", str(quantity))
    if match is None:
        raise ValueError(f"not a byte quantity: {quantity!r}")
    power = {"K": -1, "M": 0, "G": 1, "T": 2}.get((match[2] or "")[:1])
    if power is None:
        return float(match[1]) / 2**20
    return float(match[1]) * 1024.0**power


def dockerfile_instructions(text: str) -> list[tuple[str, str]]:
    """Return (INSTRUCTION, arguments) pairs of a Dockerfile, continuation lines joined."""
    joined = re.sub(r"\\\n", " ", text)
    pairs = []
    for line in joined.splitlines():
        line = line.strip()
        if line and not line.startswith("#"):
            word, _, rest = line.partition(" ")
            pairs.append((word.upper(), rest.strip()))
    return pairs


def stage_instructions(instructions: list[tuple[str, str]], name: str) -> list[tuple[str, str]]:
    """Return the instructions that make stage `name` of a multi-stage Dockerfile: those of the
    stage it is built FROM, if that is a stage of the file, then its own."""
    stages: dict[str, list[tuple[str, str]]] = {}
    current: list[tuple[str, str]] = []
    for word, rest in instructions:
        if word == "FROM":
            base, _, alias = rest.partition(" AS ")
            current = [*stages.get(base.strip(), []), (word, rest)]
            stages[alias.strip() or f"#{len(stages)}"] = current
        else:
            current.append((word, rest))
    if name not in stages:
        raise ValueError(f"no stage {name!r} in the Dockerfile")
    return stages[name]


def external_bases(instructions: list[tuple[str, str]]) -> list[str]:
    """Return the images the Dockerfile's stages start FROM that are not its own stages."""
    own, bases = set(), []
    for word, rest in instructions:
        if word == "FROM":
            base, _, alias = rest.partition(" AS ")
            if base.strip() not in own:
                bases.append(base.strip())
            own.add(alias.strip())
    return bases


def copied_sources(instructions: list[tuple[str, str]]) -> list[str]:
    """Return the source paths of the Dockerfile's COPY/ADD instructions (not --from=)."""
    sources = []
    for word, rest in instructions:
        if word in ("COPY", "ADD"):
            parts = [p for p in rest.split() if not p.startswith("--")]
            if "--from=" not in rest:
                sources += parts[:-1]
    return sources


def shm_mib(singleuser: dict[str, Any]) -> float:
    """Return the size of the memory-backed volume mounted at /dev/shm (0 if there is none)."""
    storage = singleuser.get("storage") or {}
    mounts = [m for m in storage.get("extraVolumeMounts") or [] if m["mountPath"] == "/dev/shm"]
    for mount in mounts:
        for volume in storage.get("extraVolumes") or []:
            empty = volume.get("emptyDir") or {}
            if volume["name"] == mount["name"] and empty.get("medium") == "Memory":
                return mib(empty.get("sizeLimit", "0"))
    return 0.0


def local_spawner_tail(source: str) -> list[str] | None:
    """Return the literal words after the python of `c.Spawner.cmd = [...]` in `source`."""
    for node in ast.walk(ast.parse(source)):
        if (
            isinstance(node, ast.Assign)
            and ast.unparse(node.targets[0]) == "c.Spawner.cmd"
            and isinstance(node.value, ast.List)
        ):
            return [ast.literal_eval(e) for e in node.value.elts[1:]]
    return None


# --- the files ------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def values() -> dict[str, Any]:
    return yaml.safe_load((KUBE / "values.yaml").read_text())


@pytest.fixture(scope="module")
def progress() -> dict[str, dict[str, Any]]:
    documents = list(yaml.safe_load_all((KUBE / "progress.yaml").read_text()))
    return {doc["kind"]: doc for doc in documents if doc}


@pytest.fixture(scope="module")
def capacity() -> dict[str, Any]:
    return yaml.safe_load((DEPLOY / "capacity.yaml").read_text())


@pytest.fixture(scope="module")
def dockerfile() -> list[tuple[str, str]]:
    """The learners' image of deploy/kubernetes/: the root Dockerfile's `singleuser` stage."""
    return stage_instructions(dockerfile_instructions(DOCKERFILE.read_text()), "singleuser")


def _course_module(name: str) -> Any:
    """Return module `name` of the course, or None where this branch does not have it yet.

    A module that exists but fails to import fails the test (no silent fallback).
    """
    try:
        found = importlib.util.find_spec(name)
    except ModuleNotFoundError:
        found = None
    return importlib.import_module(name) if found else None


def _service() -> tuple[str, str]:
    progress = _course_module("course_lib.hub.progress")
    if progress is None:
        return "course-progress", "COURSE_PROGRESS_URL"
    return progress.SERVICE_NAME, progress.PROGRESS_URL_ENV


def test_files_parse(values, progress) -> None:
    assert set(values) >= {"hub", "singleuser", "cull"}
    assert set(progress) == {"PersistentVolumeClaim", "Deployment", "Service", "NetworkPolicy"}


def schema_errors(document: Any, schema_name: str) -> list[str]:
    """Return where `document` breaks schemas/`schema_name` (empty when it follows it)."""
    import jsonschema

    schema = json.loads((KUBE / "schemas" / schema_name).read_text())
    validator = jsonschema.Draft7Validator(schema)
    return [
        f"{'/'.join(map(str, e.absolute_path)) or '(top)'}: {e.message}"
        for e in validator.iter_errors(document)
    ]


def test_values_follow_the_pinned_charts_schema(values) -> None:
    assert schema_errors(values, "values.schema.json") == []


def test_progress_objects_follow_the_kubernetes_shapes() -> None:
    for document in yaml.safe_load_all((KUBE / "progress.yaml").read_text()):
        assert schema_errors(document, "progress.schema.json") == [], document["kind"]


def test_the_schemas_refuse_a_misspelt_or_mistyped_key(values, progress) -> None:
    broken = json.loads(json.dumps(values))
    broken["singleuser"]["cpu"]["guarantees"] = 1.0  # closed object in the chart's schema
    broken["singleuser"]["memory"]["limit"] = ["2G"]
    broken["cull"]["timeout"] = "1h"
    broken["singleuser"]["networkPolicy"]["enable"] = True
    errors = schema_errors(broken, "values.schema.json")
    assert len(errors) == 4, errors
    deployment = json.loads(json.dumps(progress["Deployment"]))
    deployment["spec"]["template"]["spec"]["containers"][0]["port"] = 8090
    deployment["spec"]["replicas"] = "1"
    assert len(schema_errors(deployment, "progress.schema.json")) == 1  # oneOf: one error
    netpol = json.loads(json.dumps(progress["NetworkPolicy"]))
    netpol["spec"]["policyTypes"] = ["Inbound"]
    assert schema_errors(netpol, "progress.schema.json")


def image_pin(name: str) -> str:
    """Return the version of `name` the learners' image installs: image-pins.txt's, installed
    over environment.txt's, else environment.txt's."""
    for path in (KUBE / "image-pins.txt", REPO / "environment.txt"):
        text = path.read_text()
        match = re.search(rf"^{re.escape(name)}==(\S+)", text, flags=re.MULTILINE)
        if match is not None:
            return match[1]
    raise ValueError(f"neither image-pins.txt nor environment.txt pins {name}")


def test_the_chart_is_pinned_and_its_hub_runs_the_images_jupyterhub(values, dockerfile) -> None:
    chart = yaml.safe_load((KUBE / "chart.yaml").read_text())
    version = chart["version"]
    assert re.fullmatch(r"\d+\.\d+\.\d+", version), "a released chart, not a range"
    guide = GUIDE.read_text()
    header = (KUBE / "values.yaml").read_text()
    for text in (guide, header):
        installs = re.findall(r"helm upgrade --install[^\n]*(?:\\\n[^\n]*)*", text)
        assert installs, "an install command"
        assert all(f"--version {version}" in cmd for cmd in installs), installs
        assert f"JupyterHub {chart['hub_jupyterhub']}" in text
    # the hub the chart runs and the learners' jupyterhub-singleuser: one JupyterHub release
    assert chart["hub_jupyterhub"] == image_pin("jupyterhub")
    runs = [rest for word, rest in dockerfile if word == "RUN"]
    pins_install = r"pip install .*-r deploy/kubernetes/image-pins\.txt"
    assert any(re.search(pins_install, run) for run in runs), "the image installs image-pins.txt"


def test_network_policy_is_on_and_the_guide_says_the_plugin_must_enforce_it(
    values, progress
) -> None:
    policies = [
        values["hub"]["networkPolicy"],
        values["proxy"]["chp"]["networkPolicy"],
        values["proxy"]["traefik"]["networkPolicy"],
        values["singleuser"]["networkPolicy"],
    ]
    assert all(p.get("enabled") is True for p in policies)
    rules = values["singleuser"]["networkPolicy"]["egressAllowRules"]
    assert rules["privateIPs"] is False and rules["cloudMetadataServer"] is False
    selected = progress["NetworkPolicy"]["spec"]["podSelector"]["matchLabels"]
    pod = progress["Deployment"]["spec"]["template"]["metadata"]["labels"]
    assert selected.items() <= pod.items(), "the policy selects the service's pod"
    assert "network plugin must enforce NetworkPolicy" in " ".join(GUIDE.read_text().split())


def test_singleuser_runs_the_local_hubs_command(values, dockerfile) -> None:
    cmd = values["singleuser"]["cmd"]
    assert cmd == [IMAGE_PYTHON, *LOCAL_TAIL]
    cmd_line = [json.loads(rest) for word, rest in dockerfile if word == "CMD"]
    assert cmd_line[-1] == cmd, "the image's CMD is the spawner's command"
    hub_config = REPO / "course_lib" / "hub" / "hub_config.py"
    if hub_config.exists():
        assert local_spawner_tail(hub_config.read_text()) == LOCAL_TAIL
    singleuser = _course_module("course_lib.hub.singleuser")
    default_url = "/lab/tree/notebooks/01_setup_check.ipynb"
    assert values["singleuser"]["defaultUrl"] == getattr(singleuser, "DEFAULT_URL", default_url)


def test_progress_service_is_one_name_one_port(values, progress) -> None:
    name, url_env = _service()
    assert list(values["hub"]["services"]) == [name]
    url = urlsplit(values["hub"]["services"][name]["url"])
    assert url.hostname == name == progress["Service"]["metadata"]["name"]
    port = url.port
    service_port = progress["Service"]["spec"]["ports"][0]
    assert service_port["port"] == port
    container = progress["Deployment"]["spec"]["template"]["spec"]["containers"][0]
    assert [p["containerPort"] for p in container["ports"]] == [port]
    env = {e["name"]: e for e in container["env"]}
    assert urlsplit(env["JUPYTERHUB_SERVICE_URL"]["value"]).port == port
    assert env["JUPYTERHUB_SERVICE_NAME"]["value"] == name
    assert env["JUPYTERHUB_SERVICE_PREFIX"]["value"] == f"/services/{name}/"
    secret = env["JUPYTERHUB_API_TOKEN"]["valueFrom"]["secretKeyRef"]
    assert secret["key"] == f"hub.services.{name}.apiToken"
    assert values["singleuser"]["extraEnv"][url_env] == f"http://{name}:{port}/services/{name}/"
    egress = values["singleuser"]["networkPolicy"]["egress"]
    assert {p["port"] for rule in egress for p in rule["ports"]} == {port}
    assert container["args"][:3] == [IMAGE_PYTHON, "-m", "course_lib.hub.progress"]
    assert container["args"][3:] == ["--db", "/data/progress.sqlite"]
    mounts = {m["mountPath"] for m in container["volumeMounts"]}
    assert "/data" in mounts
    progress_module = _course_module("course_lib.hub.progress")
    if progress_module is not None:  # the local hub's entry: same command, same OAuth settings
        command = progress_module.service_command(IMAGE_PYTHON, Path("/data/progress.sqlite"))
        assert container["args"] == command
        spec = progress_module.service_spec(port, "")
        given = progress_module.service_environment(port, "", "")
        assert set(given) == set(env), "what the local hub's progress service is given"
        entry = values["hub"]["services"][name]
        for key in ("oauth_no_confirm", "display"):
            assert entry.get(key) == spec.get(key), key
    image = progress["Deployment"]["spec"]["template"]["spec"]["containers"][0]["image"]
    single = values["singleuser"]["image"]
    assert image == f"{single['name']}:{single['tag']}", "the same image as the learners'"


def test_roles_mirror_the_progress_service(values) -> None:
    name, _ = _service()
    progress_module = _course_module("course_lib.hub.progress")
    if progress_module is None:
        wanted = [
            {
                "name": f"{name}-service",
                "scopes": ["list:users", "read:users:name"],
                "services": [name],
            },
            {"name": "user", "scopes": ["self", f"access:services!service={name}"]},
            {
                "name": "server",
                "scopes": [
                    "users:activity!user",
                    "access:servers!server",
                    f"access:services!service={name}",
                ],
            },
        ]
    else:
        wanted = progress_module.roles()
    loaded = values["hub"]["loadRoles"]
    assert sorted(loaded) == sorted(r["name"] for r in wanted)
    for role in wanted:
        mine = loaded[role["name"]]
        for key in ("scopes", "users", "services", "groups"):
            assert sorted(mine.get(key, [])) == sorted(role.get(key, [])), (role["name"], key)


def host_cores(host: str) -> int:
    """Return the cores of deploy/capacity.yaml's `measured.host` ("2 cores (x86_64), ...")."""
    match = re.match(r"(\d+) cores?\b", host)
    if match is None:
        raise ValueError(f"no core count in measured.host: {host!r}")
    return int(match[1])


def test_requests_are_the_measured_figures(values, capacity) -> None:
    from bench._capacity_report import held_cores, pod_memory_mib, requests

    kube = capacity["kubernetes"]
    per = capacity["per_learner"]
    measured = capacity["measured"]
    cores, held = host_cores(measured["host"]), measured["learners_held"]
    cpu = held_cores(per["cpu_cores"], cores, held)
    assert kube == requests(cpu, pod_memory_mib(capacity))  # a lab's or a hub's learner
    single = values["singleuser"]
    assert single["cpu"]["guarantee"] == kube["guarantee"]["cpu"] >= per["cpu_cores"]
    # Kubernetes packs at most 1/guarantee learners per core: never more than held every goal
    assert 1 / single["cpu"]["guarantee"] <= (held or 1) / cores + 1e-9
    assert single["cpu"]["limit"] >= single["cpu"]["guarantee"]
    assert single["cpu"]["limit"] == kube["limit"]["cpu"]
    assert single["memory"]["guarantee"] == kube["guarantee"]["memory"]
    assert mib(single["memory"]["guarantee"]) >= per["memory_mib_alone"]
    hub = capacity.get("hub") or {}
    assert mib(single["memory"]["guarantee"]) >= hub.get("learner_memory_mib_alone", 0)
    assert single["memory"]["limit"] == kube["limit"]["memory"]
    assert capacity["measured"]["date"] and capacity["measured"]["host"]


def test_shm_is_memory_backed_and_big_enough(values) -> None:
    assert shm_mib(values["singleuser"]) >= SHM_MIN_MIB


def test_class_and_culler_match_the_local_hub(values) -> None:
    hub_yaml = REPO / "config" / "hub.yaml"
    if not hub_yaml.exists():
        pytest.skip("config/hub.yaml (the local hub's class) is not on this branch")
    local = yaml.safe_load(hub_yaml.read_text())
    auth = values["hub"]["config"]["Authenticator"]
    assert sorted(auth["allowed_users"]) == sorted(local["learners"])
    assert sorted(auth["admin_users"]) == sorted(local["admins"])
    assert values["cull"]["enabled"] is bool(local["idle_minutes"])
    assert values["cull"]["timeout"] == local["idle_minutes"] * 60


def test_image_is_debian_12_python_with_no_registry_host() -> None:
    bases = external_bases(dockerfile_instructions(DOCKERFILE.read_text()))
    assert bases == ["debian:bookworm-slim"]  # and Debian's CPython 3.11, as CI proves
    assert not any(names_registry_host(base) for base in bases)


def test_image_copies_paths_that_exist_and_runs_as_the_learner(dockerfile) -> None:
    sources = copied_sources(dockerfile)
    assert sources, "the image copies the course"
    missing = [s for s in sources if not (REPO / s).exists()]
    assert not missing, f"COPY sources missing from the repo: {missing}"
    words = dict(dockerfile)  # the last of each
    args = {r.partition("=")[0]: r.partition("=")[2] for w, r in dockerfile if w == "ARG"}
    assert any(w == "WORKDIR" and r == IMAGE_COURSE for w, r in dockerfile)
    assert any(w == "RUN" and r.startswith("make setup") for w, r in dockerfile)
    assert words["USER"] == "${NB_UID}" and args["NB_UID"] == "1000"
    env = " ".join(r for w, r in dockerfile if w == "ENV")
    assert "HOME=/home/${NB_USER}" in env and args["NB_USER"] == "jovyan"


def test_the_guide_names_the_files_and_the_readme_links_it() -> None:
    guide = GUIDE.read_text()
    assert guide.startswith("# A class on Kubernetes (Zero to JupyterHub)\n")
    assert "book/guides/class-on-kubernetes.md" in (REPO / "README.md").read_text()
    for path in ("--target singleuser", "values.yaml", "progress.yaml", "capacity"):
        assert path in guide


# --- the helpers fail on broken inputs --------------------------------------------------------
@pytest.mark.parametrize(
    ("image", "named"),
    [
        ("python:3.11-slim-bookworm", False),
        ("library/python:3.11", False),
        ("images.example.org/jupyter/base", True),
        ("registry.local:5000/python:3.11", True),
        ("localhost/python", True),
    ],
)
def test_registry_host_rule(image: str, named: bool) -> None:
    assert names_registry_host(image) is named


def test_broken_files_fail_the_checks() -> None:
    assert host_cores("16 cores (x86_64), 62.8 GiB") == 16
    with pytest.raises(ValueError):
        host_cores("a big one")
    assert mib("448M") == 448 and mib("2G") == 2048 and mib("256Mi") == 256
    with pytest.raises(ValueError):
        mib("lots")
    small = {
        "storage": {
            "extraVolumes": [
                {"name": "dshm", "emptyDir": {"medium": "Memory", "sizeLimit": "64Mi"}}
            ],
            "extraVolumeMounts": [{"name": "dshm", "mountPath": "/dev/shm"}],
        }
    }
    assert shm_mib(small) < SHM_MIN_MIB
    on_disk = json.loads(json.dumps(small))
    on_disk["storage"]["extraVolumes"][0]["emptyDir"] = {"sizeLimit": "1Gi"}
    assert shm_mib(on_disk) == 0.0
    broken = dockerfile_instructions("FROM python:3.11\nCOPY no_such_dir/ \\\n  /opt/x/\n")
    assert copied_sources(broken) == ["no_such_dir/"]
    two = dockerfile_instructions("FROM a AS one\nRUN x\nFROM one AS two\nRUN y\nFROM b\n")
    assert stage_instructions(two, "two") == [("FROM", "a AS one"), ("RUN", "x"),
                                              ("FROM", "one AS two"), ("RUN", "y")]  # fmt: skip
    assert external_bases(two) == ["a", "b"]
    with pytest.raises(ValueError):
        stage_instructions(two, "three")
    assert not (REPO / "no_such_dir").exists()
    assert local_spawner_tail('c.Spawner.cmd = [p, "-m", "course_lib", "lab"]') != LOCAL_TAIL
