"""`ament_copyright` (diffctl/testing/copyright.py, license_notices.py): the names its users reach for."""

from diffctl.testing.copyright import CONTRIBUTING, LICENSE, SOURCE, UNKNOWN
from diffctl.testing.license_notices import COPYRIGHT_NAMES, LICENSES

SOURCE_FILETYPE = SOURCE
CONTRIBUTING_FILETYPE = CONTRIBUTING
LICENSE_FILETYPE = LICENSE
UNKNOWN_IDENTIFIER = UNKNOWN


def get_copyright_names() -> dict[str, str]:
    return dict(COPYRIGHT_NAMES)


def get_licenses() -> dict:
    return dict(LICENSES)
