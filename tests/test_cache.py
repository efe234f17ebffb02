"""The cache directory's array store (batcert.cache): entries survive a round trip exactly,
follow the code that made them, and every failure is only a miss."""

from __future__ import annotations

import os

import numpy as np
import pytest

from batcert.cache import ArrayStore, CacheWarning, cache_dir, code_fingerprint

ARRAYS = {"a": np.linspace(0.0, 1.0, 7), "b": np.arange(6.0).reshape(2, 3),
          "s": np.array(("closed", "open")), "x": np.array(2.5), "n": np.arange(3, dtype=np.int64),
          "c": np.array([1 + 2j, 3 - 4j]), "t": np.arange(12.0).reshape(3, 4).T,
          "e": np.zeros((0, 3)), "f": np.array([True, False])}


@pytest.fixture
def where(tmp_path, monkeypatch):
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(tmp_path / "cache"))
    return tmp_path / "cache" / "things"


def same(a, b):
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


def test_an_entry_round_trips_exactly(where):
    store = ArrayStore("things", code=("batcert.cache",))
    assert store.load("k") is None
    store.save("k", ARRAYS)
    assert same(store.load("k"), ARRAYS)
    assert [p.suffix for p in where.iterdir()] == [".arrays"]  # no temporary file left


def test_entries_follow_the_code_that_made_them(where):
    ArrayStore("things", code=("batcert.cache",)).save("k", ARRAYS)
    assert ArrayStore("things", code=("batcert.units",)).load("k") is None
    assert code_fingerprint(("batcert.cache",)) != code_fingerprint(("batcert.units",))
    # a library is fingerprinted by its release file, a module by its source
    assert code_fingerprint(("numpy", "batcert.cache")) is not None


def test_no_code_no_store(where):
    store = ArrayStore("things", code=("batcert.no_such_module",))
    store.save("k", ARRAYS)
    assert store.load("k") is None
    assert not where.exists() or not any(where.iterdir())


@pytest.mark.parametrize("damage", ["foreign", "truncated", "header", "shape"])
def test_a_damaged_entry_is_a_miss_and_is_replaced(where, damage):
    store = ArrayStore("things", code=("batcert.cache",))
    store.save("k", ARRAYS)
    (path,) = where.glob("*.arrays")
    data = path.read_bytes()
    path.write_bytes({"foreign": b"PK\x03\x04 not ours",
                      "truncated": data[:len(data) // 2],
                      "header": data.replace(b'"shape"', b'"shope"', 1),
                      "shape": data.replace(b"[2, 3]", b"[9, 9]", 1)}[damage])
    with pytest.warns(CacheWarning, match="damaged"):
        assert store.load("k") is None
    store.save("k", ARRAYS)
    assert same(store.load("k"), ARRAYS)


def test_loaded_arrays_are_writable_and_arrays_of_objects_are_not_kept(where):
    store = ArrayStore("things", code=("batcert.cache",))
    store.save("k", ARRAYS)
    loaded = store.load("k")
    loaded["a"][0] = 5.0  # a private copy of the file's bytes
    assert same(store.load("k"), ARRAYS)
    store.save("objects", {"o": np.array([{}, None], dtype=object)})
    assert store.load("objects") is None


def test_an_unwritable_cache_is_passed_over(tmp_path, monkeypatch):
    (tmp_path / "file").write_text("not a directory")
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(tmp_path / "file"))
    assert cache_dir("things") is None
    store = ArrayStore("things", code=("batcert.cache",))
    store.save("k", ARRAYS)  # no error
    assert store.load("k") is None


def test_the_least_recently_used_entries_go_first(where):
    size = ArrayStore("things", code=("batcert.cache",))
    size.save("probe", ARRAYS)
    (probe,) = where.glob("*.arrays")
    one = probe.stat().st_size
    probe.unlink()
    store = ArrayStore("things", code=("batcert.cache",), limit=int(2.5 * one))
    store.save("first", ARRAYS)
    store.save("second", ARRAYS)
    old = [(p, p.stat().st_mtime) for p in where.glob("*.arrays")]
    for p, _ in old:  # make "first" the older and then read it: it becomes the recent one
        os.utime(p, (1, 1))
    assert store.load("first") is not None
    store.save("third", ARRAYS)
    assert store.load("first") is not None and store.load("third") is not None
    assert store.load("second") is None
    assert len(list(where.glob("*.arrays"))) == 2


# -- what the cache trusts: every entry's checksum (issue 40, item 2) --------------------------

def _entry(where):
    (path,) = where.glob("*.arrays")
    return path, bytearray(path.read_bytes())


@pytest.mark.parametrize("edit", ["bit flip", "doubled value", "nan", "header only"])
def test_an_entry_that_still_parses_but_was_changed_is_a_miss(where, edit):
    """A bad disk block or a hand edit leaves an entry that parses: its checksum catches it, it
    is a miss with one warning naming the file, and the next save replaces it."""
    store = ArrayStore("things", code=("batcert.cache",))
    store.save("k", ARRAYS)
    path, data = _entry(where)
    at = data.rindex(np.linspace(0.0, 1.0, 7).tobytes()) + 8 * 3  # the element a[3] = 0.5
    if edit == "bit flip":
        data[at + 2] ^= 0x10
    elif edit == "doubled value":
        data[at:at + 8] = np.float64(1.0).tobytes()
    elif edit == "nan":
        data[at:at + 8] = np.float64("nan").tobytes()
    else:  # the JSON header edited, the arrays not: "b" read as 3 x 2
        data[:] = data.replace(b"[2, 3]", b"[3, 2]", 1)
    path.write_bytes(bytes(data))
    with pytest.warns(CacheWarning, match=f"{path.name} is damaged"):
        assert store.load("k") is None
    store.save("k", ARRAYS)
    assert same(store.load("k"), ARRAYS)


def test_a_stored_entry_that_does_not_make_a_result_is_a_miss_never_a_traceback():
    """The workspace's loader of a kind raising (a missing array: KeyError) or refusing an
    intact entry is a miss: the store is told (it warns and drops it), the value recomputed."""
    from dict_store import DictStore

    from batcert import workspace

    store = DictStore()
    ws = workspace.Workspace()
    folder = workspace.KINDS["barrel-compression"].folder
    ws.attach(lambda f: store if f == folder else DictStore())

    def call():
        return ws.call("barrel-compression", _doubled, 3.0, save=lambda k: {"k": np.array(k)},
                       load=lambda a: float(a["k"]) if a["k"] > 0 else None)

    assert call() == 6.0
    (key,) = store.entries
    for bad in ({"other": np.array(1.0)}, {"k": np.array(-1.0)}):
        ws.clear()
        store.entries[key] = bad
        assert call() == 6.0
        assert store.bad == [key] and float(store.entries[key]["k"]) == 6.0
        store.bad.clear()


def _doubled(x):
    return 2.0 * x


# -- what the cache may delete: only its own entries, in its own folder (issue 40, item 1) -----

def _user_files(folder):
    folder.mkdir(parents=True, exist_ok=True)
    files = {folder / "thesis.tex": "chapter 1", folder / "data.csv": "a,b\n1,2\n",
             folder / "0123456789abcdef0123456789abcdef.arrays": "looks like ours, is not"}
    for f, text in files.items():
        f.write_text(text)
    return files


def _intact(files):
    return all(f.is_file() and f.read_text() == text for f, text in files.items())


def test_a_cache_directory_that_holds_a_users_files_is_not_used(tmp_path, monkeypatch):
    """BATCERT_CACHE_DIR pointed at a project folder: the cache says so once and keeps out; a
    trim that would delete everything (limit 0) deletes nothing."""
    project = tmp_path / "project"
    files = _user_files(project / "things")
    files.update(_user_files(project))
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(project))
    store = ArrayStore("things", code=("batcert.cache",), limit=0)
    with pytest.warns(CacheWarning, match="holds files batcert did not write"):
        store.save("k", ARRAYS)
    assert store.load("k") is None
    assert _intact(files)
    assert not (project / "CACHEDIR.TAG").exists()


def test_a_kind_folder_that_is_a_link_is_never_followed(tmp_path, monkeypatch):
    """One of the cache's folders a symlink to a user's folder (in a cache batcert made): the
    store keeps out of it."""
    users = tmp_path / "users"
    files = _user_files(users)
    root = tmp_path / "cache"
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(root))
    assert cache_dir("other") is not None  # the root is made and tagged as batcert's
    assert (root / "CACHEDIR.TAG").read_text().startswith("Signature: 8a477f597d28d172789f06886806bc55")
    (root / "things").symlink_to(users, target_is_directory=True)
    store = ArrayStore("things", code=("batcert.cache",), limit=0)
    with pytest.warns(CacheWarning, match="is a link"):
        store.save("k", ARRAYS)
    assert _intact(files)


def test_the_trim_deletes_only_the_caches_own_entries(where):
    """Files a user left in a cache folder, a link among its entries, a link to a user's file
    with an entry's name: a trim to nothing (limit 0) removes only batcert's own entries."""
    store = ArrayStore("things", code=("batcert.cache",))
    store.save("first", ARRAYS)
    outside = where.parent.parent / "outside"
    files = _user_files(outside)
    notes = where / "notes.txt"
    notes.write_text("mine")
    files[notes] = "mine"
    (where / "linked.arrays").symlink_to(outside / "data.csv")
    (where / ("f" * 32 + ".arrays")).symlink_to(outside / "thesis.tex")
    ArrayStore("things", code=("batcert.cache",), limit=0).save("second", ARRAYS)
    assert _intact(files)
    assert (where / "linked.arrays").is_symlink() and (where / ("f" * 32 + ".arrays")).is_symlink()
    assert not [p for p in where.glob("*.arrays") if not p.is_symlink()]  # its own: all gone


def test_a_folder_of_the_caches_own_entries_is_adopted(tmp_path, monkeypatch):
    """A cache directory an earlier batcert made (no tag yet, only its entries) is used and
    tagged; an empty folder likewise."""
    for name in ("old", "empty"):
        root = tmp_path / name
        root.mkdir()
        if name == "old":
            (root / "modes").mkdir()
            (root / "modes" / ("a" * 32 + ".arrays")).write_bytes(b"batcert arrays 1\n[]\n")
        monkeypatch.setenv("BATCERT_CACHE_DIR", str(root))
        store = ArrayStore("things", code=("batcert.cache",))
        store.save("k", ARRAYS)
        assert same(store.load("k"), ARRAYS)
        assert (root / "CACHEDIR.TAG").is_file()


def test_a_stale_temporary_file_is_trimmed_a_fresh_one_kept(where):
    store = ArrayStore("things", code=("batcert.cache",))
    store.save("k", ARRAYS)
    stale, fresh = where / ".batcert-abc_1.tmp", where / ".batcert-abc_2.tmp"
    for f in (stale, fresh):
        f.write_bytes(b"half an entry")
    os.utime(stale, (1, 1))
    store.save("k2", ARRAYS)
    assert not stale.exists() and fresh.exists()
