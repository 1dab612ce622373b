"""The process settings the command line makes: the glibc allocator setting (keep freed
memory for reuse) yields to the user's own glibc variables and MECHREPORT_MALLOC=default."""
from __future__ import annotations


def test_allocator_setting_respects_the_environment(monkeypatch):
    """The glibc setting the command line makes (keep freed memory for reuse) is skipped when
    the user set glibc's own variables or MECHREPORT_MALLOC=default."""
    from mechreport.app import process
    for name, value in (("MECHREPORT_MALLOC", "default"), ("MALLOC_TRIM_THRESHOLD_", "0"),
                        ("MALLOC_MMAP_THRESHOLD_", "131072")):
        with monkeypatch.context() as m:
            m.setenv(name, value)
            assert process.keep_freed_memory() is False
    import platform
    if platform.libc_ver()[0] == "glibc":        # applied where it can be
        for name in ("MECHREPORT_MALLOC", "MALLOC_TRIM_THRESHOLD_", "MALLOC_MMAP_THRESHOLD_"):
            monkeypatch.delenv(name, raising=False)     # as an earlier in-process CLI run left
        assert process.keep_freed_memory() is True
