# The tests of the test programs that take five seconds or more, with their typical seconds in a release
# build on a 2-core machine (most compile a shader of one's own): ctest -j starts them first
# (CMakeLists.txt of this folder says why). A test missing here only runs later; a name here that no
# test has fails Tests.LongTestsStartFirst.
set_tests_properties(UserShaderCli.CacheCompilesOnceAndAgainWhenTheShaderItsHeaderOrTheModuleChanges PROPERTIES COST 38)
set_tests_properties(UserShaderWalks.ADrawOfAnotherKindCompilesTheShaderOnceMoreWithEveryWalk PROPERTIES COST 23)
set_tests_properties(UserShaderCli.ReadmeShaderDrawsAndIsTraced PROPERTIES COST 20)
set_tests_properties(CompareAgainst.AShaderIsComparedWithTheBuiltInModel PROPERTIES COST 19)
set_tests_properties(UserShaderCli.SameFileNameInTwoFoldersDoesNotCollide PROPERTIES COST 19)
set_tests_properties(UserShaderCli.AShaderIsCompiledOnceForTheDrawsOfItsScene PROPERTIES COST 18)
set_tests_properties(TradeWithShader.TheKnobsAreScoredAgainstTheReferenceOfTheShader PROPERTIES COST 16)
set_tests_properties(UserShaderReference PROPERTIES COST 15)
set_tests_properties(ShaderAgainstBuiltIn PROPERTIES COST 15)
set_tests_properties(UserShaderStep.OneLaneOutputOfTheTracedPixelIsTheRenderedPixel PROPERTIES COST 10)
set_tests_properties(UserShaderStep.DiscardIsShownAndKeptFragmentsMatchTheRender PROPERTIES COST 10)
set_tests_properties(UserShaderCli.TwoRunsAtOnceBothSucceedAndOneCompiles PROPERTIES COST 9)
set_tests_properties(BenchTest.ShaderIsTimedAgainstTheBuiltInBlinnPhong PROPERTIES COST 9)
set_tests_properties(TradeRepeat.TheSameTradeTwiceAgreesOnEveryVerdict PROPERTIES COST 6)
set_tests_properties(UserShaderCli.CompileErrorPointsAtTheFileAndLine PROPERTIES COST 6)
set_tests_properties(UserShaderStep.ScreensShowTheShadersNamesRecordedValuesAndOutput PROPERTIES COST 6)
set_tests_properties(UserShaderCli.WrongPartsSayHowThePartsAreWritten PROPERTIES COST 5)
set_tests_properties(NotationWalk PROPERTIES COST 5)
