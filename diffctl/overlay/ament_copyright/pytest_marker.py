"""`ament_copyright.pytest_marker`: the `copyright` marker of the generated test_copyright.py."""


def pytest_configure(config) -> None:
    config.addinivalue_line("markers", "copyright: marks tests checking for copyright notices")
