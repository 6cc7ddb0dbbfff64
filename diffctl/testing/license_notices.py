"""The license notices `ament_copyright` recognises in a file header (the common ones of Jazzy's set).

Each notice is the license's standard per-file notice; `{copyright}` stands for the copyright line(s) and
`{copyright_holder}` for the holder's name. Matching ignores line breaks and indentation.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class License:
    name: str
    spdx: str
    file_headers: tuple[str, ...]
    license_file: str  # a passage of the full license text that names it in a LICENSE file
    contributing_file: str  # the CONTRIBUTING.md statement that contributions fall under it


_APACHE2 = """{copyright}

Licensed under the Apache License, Version 2.0 (the "License");
you may not use this file except in compliance with the License.
You may obtain a copy of the License at

    http://www.apache.org/licenses/LICENSE-2.0

Unless required by applicable law or agreed to in writing, software
distributed under the License is distributed on an "AS IS" BASIS,
WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
See the License for the specific language governing permissions and
limitations under the License."""

_DISCLAIMER_BSD = """THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS "AS IS"
AND ANY EXPRESS OR IMPLIED WARRANTIES, INCLUDING, BUT NOT LIMITED TO, THE
IMPLIED WARRANTIES OF MERCHANTABILITY AND FITNESS FOR A PARTICULAR PURPOSE
ARE DISCLAIMED. IN NO EVENT SHALL THE COPYRIGHT HOLDER OR CONTRIBUTORS BE
LIABLE FOR ANY DIRECT, INDIRECT, INCIDENTAL, SPECIAL, EXEMPLARY, OR
CONSEQUENTIAL DAMAGES (INCLUDING, BUT NOT LIMITED TO, PROCUREMENT OF
SUBSTITUTE GOODS OR SERVICES; LOSS OF USE, DATA, OR PROFITS; OR BUSINESS
INTERRUPTION) HOWEVER CAUSED AND ON ANY THEORY OF LIABILITY, WHETHER IN
CONTRACT, STRICT LIABILITY, OR TORT (INCLUDING NEGLIGENCE OR OTHERWISE)
ARISING IN ANY WAY OUT OF THE USE OF THIS SOFTWARE, EVEN IF ADVISED OF THE
POSSIBILITY OF SUCH DAMAGE."""

_REDISTRIBUTION = """Redistribution and use in source and binary forms, with or without
modification, are permitted provided that the following conditions are met:

   * Redistributions of source code must retain the above copyright
     notice, this list of conditions and the following disclaimer.

   * Redistributions in binary form must reproduce the above copyright
     notice, this list of conditions and the following disclaimer in the
     documentation and/or other materials provided with the distribution."""

_BSD3 = f"""{{copyright}}

{_REDISTRIBUTION}

   * Neither the name of the {{copyright_holder}} nor the names of its
     contributors may be used to endorse or promote products derived from
     this software without specific prior written permission.

{_DISCLAIMER_BSD}"""

_BSD3_SHORT = """{copyright}

Use of this source code is governed by a BSD-style
license that can be found in the LICENSE file or at
https://developers.google.com/open-source/licenses/bsd"""

_MIT = """{copyright}

Permission is hereby granted, free of charge, to any person obtaining a copy
of this software and associated documentation files (the "Software"), to deal
in the Software without restriction, including without limitation the rights
to use, copy, modify, merge, publish, distribute, sublicense, and/or sell
copies of the Software, and to permit persons to whom the Software is
furnished to do so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in
all copies or substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL
THE AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN
THE SOFTWARE."""

_MIT_SHORT = """{copyright}

Use of this source code is governed by an MIT-style
license that can be found in the LICENSE file or at
https://opensource.org/licenses/MIT."""

_CONTRIBUTING = ("Any contribution that you make to this repository will be under the {name}, as dictated by that "
                 "[license]({url})")

LICENSES: dict[str, License] = {
    "apache2": License(
        "Apache License, Version 2.0", "Apache-2.0", (_APACHE2,),
        "Apache License Version 2.0, January 2004 http://www.apache.org/licenses/",
        _CONTRIBUTING.format(name="Apache 2 License", url="http://www.apache.org/licenses/LICENSE-2.0.html") + ":"),
    "bsd_3clause": License(
        "3-Clause BSD License", "BSD-3-Clause", (_BSD3, _BSD3_SHORT),
        "Neither the name of the",
        _CONTRIBUTING.format(name="3-Clause BSD License", url="https://opensource.org/licenses/BSD-3-Clause") + "."),
    "mit": License(
        "MIT License", "MIT", (_MIT, _MIT_SHORT),
        "Permission is hereby granted, free of charge, to any person obtaining a copy",
        _CONTRIBUTING.format(name="MIT license", url="https://opensource.org/licenses/MIT") + "."),
}

# Copyright holders known by a short name (`--list-copyright-names`); any other holder is accepted as unknown.
COPYRIGHT_NAMES: dict[str, str] = {"osrf": "Open Source Robotics Foundation, Inc."}
