# SPDX-License-Identifier: Apache-2.0
afn_add_gtest(test_api SOURCES unit/test_api.cpp LIBS afn)
