"""``fabtiles install-viewer``: the pinned three.js tarball, checked, its few modules extracted."""

import base64
import hashlib
import io
import tarfile

import pytest
from click.testing import CliRunner

from fabtiles.cli.main import cli
from fabtiles.web import viewer_files


def _tarball(members: dict) -> bytes:
    buf = io.BytesIO()
    with tarfile.open(fileobj=buf, mode="w:gz") as tar:
        for name, data in members.items():
            info = tarfile.TarInfo(f"package/{name}")
            info.size = len(data)
            tar.addfile(info, io.BytesIO(data))
    return buf.getvalue()


def _integrity(data: bytes) -> str:
    return "sha512-" + base64.b64encode(hashlib.sha512(data).digest()).decode()


def test_install_extracts_only_the_modules(tmp_path, monkeypatch):
    files = {m: f"// {m}\n".encode() for m in viewer_files.MODULES}
    data = _tarball({**files, "../../evil.js": b"x", "src/other.js": b"y"})
    monkeypatch.setattr(viewer_files, "INTEGRITY", _integrity(data))
    written = viewer_files.install(data, tmp_path / "three")
    assert sorted(p.relative_to(tmp_path / "three").as_posix() for p in written) == sorted(
        [*viewer_files.MODULES, "VERSION"]
    )
    assert (tmp_path / "three" / "build" / "three.module.js").read_bytes() == b"// build/three.module.js\n"
    assert not (tmp_path / "evil.js").exists() and not (tmp_path / "three" / "src").exists()
    assert viewer_files.installed(tmp_path / "three")
    assert (tmp_path / "three" / "VERSION").read_text().startswith(f"{viewer_files.VERSION} three.js")
    (tmp_path / "three" / "LICENSE").unlink()
    assert not viewer_files.installed(tmp_path / "three")


def test_changed_tarball_is_refused(tmp_path):
    data = _tarball(dict.fromkeys(viewer_files.MODULES, b""))
    with pytest.raises(viewer_files.ViewerFilesError, match=r"sha512 is not npm's integrity for three 0\.187\.0"):
        viewer_files.install(data, tmp_path / "three")
    assert not (tmp_path / "three").exists()


def test_tarball_missing_a_module(tmp_path, monkeypatch):
    data = _tarball({"LICENSE": b"MIT"})
    monkeypatch.setattr(viewer_files, "INTEGRITY", _integrity(data))
    with pytest.raises(viewer_files.ViewerFilesError, match=r"the three.js tarball has no build/three.module.js"):
        viewer_files.install(data, tmp_path / "three")


def test_no_internet_says_what_to_do(monkeypatch):
    def offline(*a, **k):
        raise OSError("network is unreachable")

    monkeypatch.setattr(viewer_files.urllib.request, "urlopen", offline)
    with pytest.raises(
        viewer_files.ViewerFilesError, match=r"could not download .*npm pack three@0\.187\.0.*--tarball"
    ):
        viewer_files.download()


def test_cli_bad_tarball_is_one_line_exit_2(tmp_path):
    bad = tmp_path / "three.tgz"
    bad.write_bytes(_tarball({"LICENSE": b"MIT"}))
    res = CliRunner().invoke(cli, ["install-viewer", "--tarball", str(bad)])
    assert res.exit_code == 2
    assert res.output.strip().splitlines() == [
        "fabtiles: error: the three.js tarball's sha512 is not npm's integrity for three 0.187.0 "
        "(a changed or truncated "
        "download); nothing was installed: fetch it again, or give the tarball of `npm pack three@0.187.0` "
        "with --tarball"
    ]


def test_cli_installs_from_a_tarball(tmp_path, monkeypatch):
    data = _tarball(dict.fromkeys(viewer_files.MODULES, b"//"))
    (tmp_path / "three.tgz").write_bytes(data)
    monkeypatch.setattr(viewer_files, "INTEGRITY", _integrity(data))
    monkeypatch.setattr(viewer_files, "VENDOR", tmp_path / "vendor")
    res = CliRunner().invoke(cli, ["install-viewer", "--tarball", str(tmp_path / "three.tgz")])
    assert res.exit_code == 0, res.output
    assert res.output.startswith("installed three.js 0.187.0 (8 files") and viewer_files.installed(tmp_path / "vendor")
